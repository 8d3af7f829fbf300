"""Resident workers: the next build uses the workers the last one left, with real processes,
real MuJoCo and the real command line, and builds exactly what a build with new workers does."""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from mjcfbuild.engine import resident
from mjcfbuild.engine.workers import WorkerPool
from mjcfbuild.errors import EXIT_INTERRUPTED, EXIT_OK, TaskCrashed, UsageError
from tests.conftest import ROOT, copy_example, run_cli
from tests.engine.test_determinism import _assert_identical
from tests.engine.test_workers import _wait_for

STEPS = "tests.engine.misbehaving_steps"


@pytest.fixture
def residents(tmp_path, monkeypatch):
    """A private folder for resident workers, on for this test; every worker in it is
    stopped afterwards. Short, in /tmp: a socket's path is limited to 108 bytes."""
    folder = Path(tempfile.mkdtemp(prefix="mjr-", dir="/tmp"))
    monkeypatch.setenv(resident.DIR_VARIABLE, str(folder))
    monkeypatch.setenv(resident.VARIABLE, "300")
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    yield folder
    for pid in resident.resident_pids(folder):
        resident.stop(pid)
    shutil.rmtree(folder, ignore_errors=True)


def _waiting(folder: Path, count: int) -> list[int]:
    """The ``count`` workers waiting in ``folder``, once they all listen again (a worker
    takes a moment after its build lets go)."""
    _wait_for(lambda: len(resident.resident_pids(folder)) == count)
    return resident.resident_pids(folder)


def _edit_forearm(arm: Path) -> None:
    mesh = arm / "meshes" / "forearm.obj"
    mesh.write_text(mesh.read_text().replace(" 0.240000", " 0.330000"))


def test_the_next_build_uses_the_workers_the_last_left_and_builds_the_same_bytes(
    residents, tmp_path
):
    arm = copy_example("arm", tmp_path / "resident")
    # run_cli captures the build's output: it returns only if the workers that stay do not
    # hold the build's output pipes open.
    assert run_cli("build", "-q", "-j", "2", cwd=arm).code == EXIT_OK
    waiting = _waiting(residents, 2)
    _edit_forearm(arm)
    result = run_cli("build", "-j", "2", cwd=arm)
    assert result.code == EXIT_OK, result.stderr
    # The same processes served it, and wait again.
    _wait_for(lambda: resident.resident_pids(residents) == waiting)
    # The same edit built by new workers: the same model, meshes and pictures.
    fresh = copy_example("arm", tmp_path / "fresh")
    _edit_forearm(fresh)
    env = {resident.VARIABLE: "0", "MJCFBUILD_CACHE_DIR": str(tmp_path / "cache-fresh")}
    assert run_cli("build", "-q", "-j", "2", cwd=fresh, env=env).code == EXIT_OK
    _assert_identical(arm / "mjcf", fresh / "mjcf")
    pictures = sorted((arm / "mjcf" / "report" / "previews").glob("*.png"))
    assert len(pictures) == 4
    fresh_pictures = fresh / "mjcf" / "report" / "previews"
    for picture in pictures:
        assert picture.read_bytes() == (fresh_pictures / picture.name).read_bytes()


def test_workers_of_other_code_or_start_variables_are_not_used(residents, tmp_path):
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [first] = _waiting(residents, 1)
    (arm / "mjcf" / "example_arm.xml").unlink()
    env = {"OMP_NUM_THREADS": "2"}  # read by OpenMP as a process starts
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm, env=env).code == EXIT_OK
    waiting = _waiting(residents, 2)
    assert first in waiting  # a new one served it; the first still waits


def test_the_key_follows_start_variables_only():
    base = {"HOME": "/home/a", "MUJOCO_GL": "egl", "PYTHONHASHSEED": "0"}
    key = resident.worker_key(base)
    assert resident.worker_key({**base, "HOME": "/home/b", "GIT_INDEX_FILE": "x"}) == key
    assert resident.worker_key({**base, "MUJOCO_GL": "osmesa"}) != key
    assert resident.worker_key({**base, "LD_LIBRARY_PATH": "/opt"}) != key


def test_a_worker_killed_while_it_waits_is_replaced(residents, tmp_path):
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [killed] = _waiting(residents, 1)
    os.kill(killed, signal.SIGKILL)
    _edit_forearm(arm)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [replacement] = _waiting(residents, 1)
    assert replacement != killed
    assert not list(residents.glob(f"*-{killed}.sock"))  # its socket was cleared away


def test_an_interrupted_build_stops_the_worker_running_its_step(residents, tmp_path):
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [before] = _waiting(residents, 1)
    _edit_forearm(arm)
    # The step asks the build to stop (as Ctrl-C would) and carries on for two seconds: the
    # build must not leave it running, since it would write after the build ended.
    env = {"MJCFBUILD_FAILPOINT": "mesh:interrupt"}
    result = run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm, env=env)
    assert result.code == EXIT_INTERRUPTED, result.stderr
    _wait_for(lambda: not resident.running(before))
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    assert "0 run" in run_cli("build", "--no-check", cwd=arm).stdout


def test_workers_leave_when_no_build_comes_in_time(residents, tmp_path, monkeypatch):
    monkeypatch.setenv(resident.VARIABLE, "0.5")
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    _wait_for(lambda: not list(residents.glob("*.sock")))


def test_crashes_and_hangs_in_resident_workers_fail_only_their_step(residents, tmp_path):
    pool = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        with pytest.raises(TaskCrashed) as info:
            pool.run(f"{STEPS}:segfault", {}, "mesh:link3", tmp_path / "crash.log", timeout=60)
        assert "mesh:link3" in info.value.one_line() and "SIGSEGV" in info.value.one_line()
        with pytest.raises(TaskCrashed, match="did not finish within 1 s"):
            pool.run(f"{STEPS}:hang", {}, "decompose:x", None, timeout=1.0)
        first = pool.run(f"{STEPS}:echo", {"x": 1}, "echo", tmp_path / "a.log", timeout=60)
        assert first["x"] == 1
        assert "C-level output" in (tmp_path / "a.log").read_text()
    finally:
        pool.close()
    # The worker that answered waits for the next build, which gets it.
    assert _waiting(residents, 1) == [first["pid"]]
    again = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        assert again.run(f"{STEPS}:echo", {}, "echo", None, timeout=60)["pid"] == first["pid"]
    finally:
        again.close()


def test_a_worker_whose_build_went_away_during_a_step_stops(tmp_path):
    ours, theirs = socket.socketpair()
    script = (
        "import socket, sys, time\n"
        "from mjcfbuild.engine.worker_main import _ClientWatch\n"
        "watch = _ClientWatch(socket.socket(fileno=int(sys.argv[1])))\n"
        "with watch.step():\n"
        "    print('step', flush=True)\n"
        "    time.sleep(120)\n"
    )
    process = subprocess.Popen(
        [sys.executable, "-c", script, str(theirs.fileno())],
        pass_fds=(theirs.fileno(),),
        stdout=subprocess.PIPE,
        cwd=ROOT,
    )
    theirs.close()
    assert process.stdout is not None and process.stdout.readline() == b"step\n"
    ours.close()  # the build is gone
    assert process.wait(timeout=60) == 3


def _box_model(folder: Path, half: float) -> Path:
    mesh = folder / "box.obj"
    corners = [(x, y, z) for x in (-half, half) for y in (-half, half) for z in (-half, half)]
    faces = "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\n"
    faces += "f 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n"
    mesh.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in corners) + faces)
    model = folder / "box.xml"
    model.write_text(
        '<mujoco><asset><mesh name="box" file="box.obj"/></asset><worldbody><body>'
        '<freejoint/><geom type="mesh" mesh="box"/></body></worldbody></mujoco>'
    )
    return model


def test_a_build_within_the_second_the_last_ended_finds_meshes_read_again(tmp_path):
    import mujoco

    from mjcfbuild.engine.worker_main import _Between, _keep_or_forget_meshes

    def size(path: Path) -> float:
        return float(mujoco.MjModel.from_xml_path(str(path)).mesh_vert.max())

    second = int(time.time()) - 10
    model = _box_model(tmp_path, 0.5)
    os.utime(tmp_path / "box.obj", (second + 0.2, second + 0.2))
    assert size(model) == pytest.approx(0.5)
    _box_model(tmp_path, 1.0)  # rewritten within the same second: MuJoCo cannot tell
    os.utime(tmp_path / "box.obj", (second + 0.7, second + 0.7))
    assert size(model) == pytest.approx(0.5)
    between = _Between()
    between.holds = "model"
    between.last_end = time.time()  # the last build ended this second
    _keep_or_forget_meshes(between)
    assert size(model) == pytest.approx(1.0)
    assert between.holds is None


def test_the_folder_must_be_private_and_short(tmp_path):
    shared = tmp_path / "shared"
    shared.mkdir(mode=0o777)
    shared.chmod(0o777)
    assert resident.resident_dir({resident.DIR_VARIABLE: str(shared)}) is None
    assert resident.resident_dir({resident.DIR_VARIABLE: "/tmp/" + "x" * 100}) is None
    private = Path(tempfile.mkdtemp(dir="/tmp"))
    try:
        assert resident.resident_dir({resident.DIR_VARIABLE: str(private)}) == private
    finally:
        private.rmdir()


@pytest.mark.parametrize("value", ["soon", "-1", "inf", "nan"])
def test_a_bad_wait_is_a_one_line_usage_error(value, arm):
    with pytest.raises(UsageError, match=f"{resident.VARIABLE}={value}"):
        resident.idle_seconds({resident.VARIABLE: value})
    result = run_cli("build", cwd=arm, env={resident.VARIABLE: value})
    assert result.code == 2 and "Traceback" not in result.stderr
    assert result.stderr.count("\n") == 1 and resident.VARIABLE in result.stderr


def test_off_by_zero_or_in_ci():
    assert resident.idle_seconds({resident.VARIABLE: "0"}) == 0
    assert resident.idle_seconds({"CI": "true"}) == 0
    assert resident.idle_seconds({"CI": "true", resident.VARIABLE: "60"}) == 60
    assert resident.idle_seconds({}) == resident.DEFAULT_SECONDS


def test_a_pool_with_resident_workers_off_starts_its_own(tmp_path, monkeypatch):
    monkeypatch.setenv(resident.VARIABLE, "0")
    pool = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        assert pool.residents is None
        pid = pool.run(f"{STEPS}:echo", {}, "echo", None, timeout=60)["pid"]
    finally:
        pool.close()
    with contextlib.suppress(ChildProcessError):
        os.waitpid(pid, 0)
    assert not resident.running(pid)
