"""Running a build: everything a build writes in its output folder is written under the
folder's lock, so builds of one folder never trip over each other (real processes, real
flock)."""

from __future__ import annotations

import fcntl
import os
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

from mjcfbuild import filesig
from mjcfbuild.engine import report, runner, stamp
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.progress import Progress
from mjcfbuild.graph.hashes import HashCache
from tests.conftest import ROOT


def _locked(state: Path) -> bool:
    """Whether some open file holds the lock of the output folder whose state is ``state``."""
    with open(state / "lock", "a") as probe:
        try:
            fcntl.flock(probe, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return True
        fcntl.flock(probe, fcntl.LOCK_UN)
        return False


def test_hashes_stamp_and_report_are_written_under_the_lock(arm, tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    # The example was copied just now: its files are "racily clean" (filesig) and would not be
    # recorded; this test is about where the records are written, not which.
    monkeypatch.setattr(filesig, "RACY_NS", 0)
    ctx = BuildContext.from_manifest_file(arm / "robot.yaml", jobs=1, run_check=False)
    ctx = replace(ctx, noop_stamp=True)
    seen: dict[str, bool] = {}

    def watch(name, function):
        def watched(*args, **kwargs):
            seen[name] = seen.get(name, True) and _locked(ctx.state_dir)
            return function(*args, **kwargs)

        return watched

    save = HashCache.save

    def save_hashes(self):  # a save with something to write
        if self._dirty:
            seen["hashes"] = seen.get("hashes", True) and _locked(ctx.state_dir)
        save(self)

    monkeypatch.setattr(HashCache, "save", save_hashes)
    monkeypatch.setattr(stamp, "record_build", watch("stamp", stamp.record_build))
    # The runner imports the report's module once the model is built: watch it there.
    monkeypatch.setattr(report, "write_report", watch("report", report.write_report))
    result = runner.run_build(ctx, Progress(quiet=True))
    assert result.ok, result.errors
    assert seen == {"hashes": True, "stamp": True, "report": True}


def test_concurrent_builds_of_one_folder_all_succeed(arm, tmp_path):
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])),
        "MJCFBUILD_CACHE_DIR": str(tmp_path / "cache"),
        "MJCFBUILD_RESIDENT_WORKERS": "0",
        "MJCFBUILD_FULL_BUILD": "1",  # every build takes the lock, none the no-op path
    }
    command = [sys.executable, "-m", "mjcfbuild", "build", "-q", "--no-check", "-j", "1"]
    first = subprocess.run(command, cwd=arm, env=env, capture_output=True, text=True)
    assert first.returncode == 0, first.stderr
    builds = [
        subprocess.Popen(command, cwd=arm, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        for _ in range(16)
    ]
    failures = []
    for build in builds:
        _, err = build.communicate(timeout=600)
        if build.returncode != 0:
            failures.append(err.decode())
    assert failures == []


def test_a_folder_removed_while_the_build_runs_fails_it_in_one_line(arm):
    """``rm -rf mjcf`` during a build: its steps failed on files gone with the folder, as
    internal errors (exit 70) or doit's words, or it even succeeded with its early outputs
    gone. The build stops here, between its planning and its building, and the folder goes."""
    import shutil
    import signal

    from mjcfbuild.errors import EXIT_OUTPUT
    from tests.conftest import sigint_at_default

    build = subprocess.Popen(
        [sys.executable, "-m", "mjcfbuild", "build", "-q", "--no-check"],
        cwd=arm,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT), "MJCFBUILD_FAILPOINT": "stages:stop"},
        preexec_fn=sigint_at_default,
    )
    _, status = os.waitpid(build.pid, os.WUNTRACED)
    assert os.WIFSTOPPED(status)
    shutil.rmtree(arm / "mjcf")
    os.kill(build.pid, signal.SIGCONT)
    _, stderr = build.communicate(timeout=300)
    assert build.returncode == EXIT_OUTPUT, stderr
    assert stderr.splitlines()[0] == (
        "mjcfbuild: error: mjcf: was removed while the build ran; nothing in it is current "
        "(build again)"
    ), stderr
    assert "Traceback" not in stderr and "internal error" not in stderr
