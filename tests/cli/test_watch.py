"""``mjcfbuild watch``: a real watching process on the example arm, edited as a user would."""

from __future__ import annotations

import os
import queue
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import pytest

from mjcfbuild.cli import run
from mjcfbuild.engine import stamp
from mjcfbuild.errors import EXIT_RESTART, EXIT_TERMINATED
from tests.conftest import ROOT, copy_example, run_cli, sigint_at_default

# Generous: a line comes when a build ends, and CI machines are slow and busy.
LINE_SECONDS = 120


class Watching:
    """A ``mjcfbuild watch`` process and the lines it printed, read as they come."""

    def __init__(self, folder: Path, *args: str, env: dict | None = None) -> None:
        self.process = subprocess.Popen(
            [sys.executable, "-m", "mjcfbuild", "watch", "--no-check", *args],
            cwd=folder,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env={**os.environ, "PYTHONPATH": str(ROOT), **(env or {})},
            preexec_fn=sigint_at_default,
        )
        self.lines: list[str] = []
        self._queue: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self._queue.put(line.rstrip("\n"))
        self._queue.put(None)

    def until(self, pattern: str) -> list[str]:
        """The lines printed up to and including the next one matching ``pattern``."""
        seen = []
        deadline = time.monotonic() + LINE_SECONDS
        while True:
            try:
                line = self._queue.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                pytest.fail(f"no line matching {pattern!r}; printed: {self.lines}")
            if line is None:
                pytest.fail(f"watch ended before {pattern!r}; printed: {self.lines}")
            self.lines.append(line)
            seen.append(line)
            if re.search(pattern, line):
                return seen

    def stop(self) -> int:
        """Ctrl-C, as at the terminal; the exit code."""
        if self.process.poll() is None:
            os.kill(self.process.pid, signal.SIGCONT)
            self.process.send_signal(signal.SIGINT)
        return self.process.wait(timeout=LINE_SECONDS)


@pytest.fixture
def watching(arm):
    started: list[Watching] = []

    def start(*args: str, env: dict | None = None) -> Watching:
        started.append(Watching(arm, *args, env=env))
        return started[-1]

    yield start
    for process in started:
        if process.process.poll() is None:
            process.process.kill()
            process.process.wait()


def _longer_forearm(arm: Path) -> None:
    mesh = arm / "meshes" / "forearm.obj"
    mesh.write_text(mesh.read_text().replace(" 0.240000", " 0.250000"))


def _forearm_assets(arm: Path) -> dict[str, bytes]:
    """The published forearm meshes (one per material) and their bytes."""
    return {path.name: path.read_bytes() for path in (arm / "mjcf" / "assets").glob("forearm*")}


def test_it_builds_each_edit_says_what_failed_and_stops_at_ctrl_c(arm, watching):
    watch = watching()
    first = watch.until(r"^mjcfbuild: watching \d+ files for changes \(Ctrl-C to stop\)$")
    assert any(line.startswith("mjcfbuild: built example_arm.xml") for line in first)
    before = _forearm_assets(arm)

    # Touched with the same bytes: the stamp still holds, so that alone builds nothing. The
    # watch asks the stamp, which then records the new times: once it has, the watch has
    # decided (a build would have discarded the stamp first), and the edit follows.
    stamp_file = stamp.stamp_path(arm / "robot.yaml", False)
    recorded = stamp_file.read_bytes()
    for mesh in (arm / "meshes").iterdir():
        os.utime(mesh)
    while stamp_file.exists() and stamp_file.read_bytes() == recorded:
        assert watch.process.poll() is None
        time.sleep(0.01)
    assert stamp_file.exists() and watch.lines == first
    _longer_forearm(arm)
    rebuild = watch.until(r"^mjcfbuild: watching \d+ files for changes$")
    assert rebuild[0] == "mjcfbuild: meshes/forearm.obj changed: building robot.yaml"
    assert any(line.startswith("mjcfbuild: model ready: mjcf/example_arm.xml") for line in rebuild)
    after = _forearm_assets(arm)
    assert before and after.keys() == before.keys() and after != before

    xacro = arm / "urdf" / "arm.urdf.xacro"
    text = xacro.read_text()
    xacro.write_text(text.replace("<robot ", "<robotx ", 1))
    failed = watch.until(r"^mjcfbuild: watching \d+ files for changes$")
    assert any(re.match(r"mjcfbuild: error: urdf/arm\.urdf\.xacro:\d+", line) for line in failed)
    xacro.write_text(text)  # fixed: built again, from the same watch
    fixed = watch.until(r"^mjcfbuild: watching \d+ files for changes$")
    assert any(line.startswith("mjcfbuild: built example_arm.xml") for line in fixed)

    assert watch.stop() == 0  # Ctrl-C while waiting ends it: the last build succeeded
    watch.until(r"^mjcfbuild: stopped watching$")


def test_sigterm_while_waiting_ends_it_with_143(arm, watching):
    """`mjcfbuild watch &` ignores SIGINT and is stopped with SIGTERM: it says it stopped and
    exits 143 (128 + SIGTERM), which the process killed by the signal only implied."""
    watch = watching()
    watch.until(r"^mjcfbuild: watching \d+ files for changes \(Ctrl-C to stop\)$")
    watch.process.send_signal(signal.SIGTERM)
    assert watch.process.wait(timeout=LINE_SECONDS) == EXIT_TERMINATED
    watch.until(r"^mjcfbuild: stopped watching$")


def test_an_edit_made_while_a_build_runs_is_built(arm, watching, tmp_path):
    """The first build stops where it would write its stamp; the mesh is edited there. That
    build may have read the mesh before the edit, so it leaves no stamp and the watch builds
    again with the edit (a stamp written then would call the older model current)."""
    watch = watching(
        env={
            "MJCFBUILD_FAILPOINT": "stamp:stop-once",
            "MJCFBUILD_FAILPOINT_ONCE_DIR": str(tmp_path),
        }
    )
    _, status = os.waitpid(watch.process.pid, os.WUNTRACED)
    assert os.WIFSTOPPED(status)
    _longer_forearm(arm)
    os.kill(watch.process.pid, signal.SIGCONT)
    watch.until(r"^mjcfbuild: watching \d+ files for changes \(Ctrl-C to stop\)$")
    rebuild = watch.until(r"^mjcfbuild: watching \d+ files for changes$")
    assert rebuild[0] == "mjcfbuild: meshes/forearm.obj changed: building robot.yaml"
    # What a build from nothing makes of the edited mesh.
    fresh = copy_example("arm", tmp_path / "fresh")
    shutil.copy(arm / "meshes" / "forearm.obj", fresh / "meshes" / "forearm.obj")
    assert run(["build", str(fresh / "robot.yaml"), "-q", "--no-check"]) == 0
    assert _forearm_assets(arm) == _forearm_assets(fresh)
    assert watch.stop() == 0


def test_a_change_to_mjcfbuild_itself_ends_it(arm, watching, tmp_path):
    """The watch runs the code it started with: when a watched file of mjcfbuild's own or
    of an installed package changes, it says so and ends (it would otherwise build with old
    code). Shown with a package folder of its own on PYTHONPATH, which it watches."""
    packages = tmp_path / "packages"
    packages.mkdir()
    watch = watching(env={"PYTHONPATH": os.pathsep.join([str(ROOT), str(packages)])})
    watch.until(r"^mjcfbuild: watching")
    (packages / "new_package.py").write_text("")  # an installed package
    ended = watch.until(r"start it again$")
    assert ended[-1].startswith(f"mjcfbuild: {packages} changed: mjcfbuild or an installed")
    # Not the last build's 0: a script that runs it in a loop tells that it should start it
    # again from a Ctrl-C.
    assert watch.process.wait(timeout=LINE_SECONDS) == EXIT_RESTART == 75


def test_a_build_waits_while_a_changed_file_is_empty(tmp_path, monkeypatch):
    """Saving truncates a file and writes it after: the build waits for the bytes (a
    benchmark's URDF edit was once built empty, on a busy machine)."""
    from mjcfbuild.cli import watch
    from mjcfbuild.engine.watched import Watched

    urdf = tmp_path / "robot.urdf"
    urdf.write_text("<robot/>")
    watched = Watched.take([str(urdf)])
    urdf.write_text("")
    pauses: list[float] = []

    def pause(seconds: float) -> None:
        pauses.append(seconds)
        if len(pauses) == 3:
            urdf.write_text('<robot name="arm"/>')  # written at last, during the third

    monkeypatch.setattr(watch.time, "sleep", pause)
    assert watch._settled(watched, [str(urdf)]) == [str(urdf)]
    assert len(pauses) == 4  # empty, empty, written, then unchanged for one pause


def test_with_resident_workers_an_edit_builds_what_a_fresh_build_does(arm, watching, tmp_path):
    """As at a terminal, where resident workers are on by default: the rebuild after an edit
    runs in the workers the first build left (which hold MuJoCo's mesh cache), and its model
    and meshes are the bytes a build from nothing makes of the edit."""
    from mjcfbuild.engine import resident
    from tests.engine.test_determinism import _assert_identical
    from tests.engine.test_workers import _wait_for

    folder = Path(tempfile.mkdtemp(prefix="mjw-", dir="/tmp"))  # a socket's path is short
    try:
        env = {resident.VARIABLE: "300", resident.DIR_VARIABLE: str(folder)}
        watch = watching("-j", "2", env=env)
        watch.until(r"^mjcfbuild: watching \d+ files for changes \(Ctrl-C to stop\)$")
        _wait_for(lambda: len(resident.resident_pids(folder)) == 2)
        waiting = resident.resident_pids(folder)  # the workers the first build left
        _longer_forearm(arm)
        rebuild = watch.until(r"^mjcfbuild: watching \d+ files for changes$")
        assert rebuild[0] == "mjcfbuild: meshes/forearm.obj changed: building robot.yaml"
        assert any(line.startswith("mjcfbuild: built example_arm.xml") for line in rebuild)
        _wait_for(lambda: resident.resident_pids(folder) == waiting)  # they served it
        assert watch.stop() == 0
        fresh = copy_example("arm", tmp_path / "fresh")
        shutil.copy(arm / "meshes" / "forearm.obj", fresh / "meshes" / "forearm.obj")
        assert run(["build", str(fresh / "robot.yaml"), "-q", "--no-check"]) == 0
        _assert_identical(arm / "mjcf", fresh / "mjcf")
    finally:
        for pid in resident.resident_pids(folder):
            resident.stop(pid)
        shutil.rmtree(folder, ignore_errors=True)


def test_a_file_a_failed_build_looked_for_is_built_when_it_comes(arm, watching):
    """After a build that failed for a missing include, creating the file did nothing: only
    the files there were then were watched."""
    xacro = arm / "urdf" / "arm.urdf.xacro"
    text = xacro.read_text()
    xacro.write_text(text.replace("</robot>", '<xacro:include filename="more.xacro"/></robot>'))
    watch = watching()
    failed = watch.until(r"^mjcfbuild: watching \d+ files for changes \(Ctrl-C to stop\)$")
    assert any("more.xacro" in line and "error" in line for line in failed), failed
    (arm / "urdf" / "more.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>\n'
    )
    built = watch.until(r"^mjcfbuild: watching \d+ files for changes$")
    assert built[0] == "mjcfbuild: urdf/more.xacro changed: building robot.yaml", built
    assert any(line.startswith("mjcfbuild: built example_arm.xml") for line in built), built
    assert watch.stop() == 0


def test_a_manifest_that_is_not_there_ends_it_at_once(arm):
    """A misspelt name said 'manifest not found', then watched forever for nothing."""
    result = run_cli("watch", "robto.yaml", cwd=arm)
    assert result.code == 3
    assert result.stderr.startswith("mjcfbuild: error: robto.yaml: manifest not found")
    assert "watching" not in result.stdout
