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
VERTICES = "tests.engine.mujoco_steps:mesh_vertices"


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
    assert len(pictures) == 7  # previews: three-quarter, side, close-up (two kinds each), top
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
    assert resident.worker_key({**base, "MALLOC_TRIM_THRESHOLD_": "0"}) != key


def test_the_key_is_the_same_however_the_command_is_started(tmp_path):
    """`mjcfbuild` (a console script: its bin/ first on sys.path, run by python3) and
    `python -m mjcfbuild` (the folder it runs in first) must find the same workers."""
    script = tmp_path / "bin" / "key.py"
    script.parent.mkdir()
    printing = "import os\nfrom mjcfbuild.engine import resident\n"
    printing += "print(resident.worker_key({'MUJOCO_GL': 'egl'}))\n"
    script.write_text(printing)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}

    def key(*command: str) -> str:
        done = subprocess.run(command, capture_output=True, text=True, env=env, cwd=tmp_path)
        assert done.returncode == 0, done.stderr
        return done.stdout.strip()

    keys = {key(sys.executable, str(script)), key(sys.executable, "-c", printing)}
    (script.parent / "new-console-script").write_text("")  # a package installed a script
    keys.add(key(sys.executable, str(script)))
    other = Path(sys.executable).with_name("python" if sys.executable[-1] == "3" else "python3")
    if other.exists() and os.path.realpath(other) == os.path.realpath(sys.executable):
        keys.add(key(str(other), str(script)))
    assert len(keys) == 1, keys


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


@pytest.mark.parametrize("variable", ["MJCFBUILD_WORKER_ANSWER_SECONDS", "MJCFBUILD_RESIDENT_MAX"])
def test_a_bad_deadline_or_cap_is_a_one_line_usage_error(variable, arm):
    env = {resident.VARIABLE: "60", variable: "-3"}
    result = run_cli("build", "--no-check", cwd=arm, env=env)
    assert result.code == 2 and "Traceback" not in result.stderr, result.stderr
    assert variable in result.stderr and result.stderr.count("\n") <= 2


def test_off_by_zero_or_in_ci():
    assert resident.idle_seconds({resident.VARIABLE: "0"}, interactive=True) == 0
    assert resident.idle_seconds({"CI": "true"}, interactive=True) == 0
    assert resident.idle_seconds({"CI": "true", resident.VARIABLE: "60"}) == 60
    assert resident.idle_seconds({}, interactive=True) == resident.DEFAULT_SECONDS


@pytest.mark.parametrize(
    "variable",
    [
        ("CI", "1"),
        ("JENKINS_URL", "https://jenkins.example/"),
        ("TF_BUILD", "True"),
        ("GITLAB_CI", "true"),
        ("GITHUB_ACTIONS", "true"),
        ("BUILDKITE", "true"),
        ("CIRCLECI", "true"),
        ("CI", "woodpecker"),
        ("CI_PIPELINE_ID", "17"),
        ("TEAMCITY_VERSION", "2024.1"),
        ("PRE_COMMIT", "1"),
        ("GIT_INDEX_FILE", "/repo/.git/index"),
    ],
)
def test_off_by_default_in_every_common_ci_and_in_hooks(variable):
    name, value = variable
    assert resident.idle_seconds({name: value}, interactive=True) == 0
    assert name in (resident.why_off({name: value}, interactive=True) or "")
    # The documented switch turns them on anyway.
    assert resident.idle_seconds({name: value, resident.VARIABLE: "60"}) == 60


def test_on_by_default_only_where_a_person_waits_at_a_terminal():
    assert resident.idle_seconds({"CI": "false"}, interactive=True) == resident.DEFAULT_SECONDS
    assert resident.idle_seconds({}, interactive=False) == 0
    assert resident.why_off({}, interactive=False) == "no terminal waits for the next build"


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


# --- Issue 32: deadlines, identities, process state, good citizenship -------------------------


def _socket_of(folder: Path, pid: int) -> Path:
    [path] = folder.glob(f"*-{pid}.sock")
    return path


def _gone(pid: int) -> bool:
    """Whether ``pid`` no longer runs (an ended worker may stay a zombie until reaped)."""
    return not resident._process_exists(pid)


def test_a_stopped_worker_is_killed_and_the_build_goes_on_with_a_fresh_one(
    residents, tmp_path, monkeypatch
):
    monkeypatch.setenv("MJCFBUILD_WORKER_ANSWER_SECONDS", "1")
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [stopped] = _waiting(residents, 1)
    os.kill(stopped, signal.SIGSTOP)  # as a debugger attached to it would
    try:
        _edit_forearm(arm)
        # run_cli gives up after 600 s: before, this build waited forever for its answer.
        result = run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm)
        assert result.code == EXIT_OK, result.stderr
        _wait_for(lambda: _gone(stopped))
        [fresh] = _waiting(residents, 1)
        assert fresh != stopped
        assert not list(residents.glob(f"*-{stopped}.sock"))
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.kill(stopped, signal.SIGKILL)


def test_workers_stop_ends_a_stopped_worker(residents, tmp_path, monkeypatch):
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [stopped] = _waiting(residents, 1)
    os.kill(stopped, signal.SIGSTOP)
    try:
        result = run_cli("workers", "stop", env={"MJCFBUILD_WORKER_ANSWER_SECONDS": "1"})
        assert result.code == EXIT_OK and "stopped 1 waiting worker" in result.stdout
        _wait_for(lambda: _gone(stopped))
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.kill(stopped, signal.SIGKILL)


def _stale_socket(path: Path) -> None:
    """A socket file nobody listens on, as a killed worker leaves."""
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(str(path))
    listener.close()


def test_a_stale_socket_naming_another_process_is_removed_never_signalled(residents, tmp_path):
    # An unrelated process of this user (after PIDs wrapped, the killed worker's number),
    # and one of another user (process 1), which the old code signalled.
    unrelated = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"])
    try:
        key = "0" * 20
        _stale_socket(residents / f"{key}-{unrelated.pid}.sock")
        if os.getuid() != 0:  # the unprivileged user of the report; never risk it as root
            _stale_socket(residents / f"{key}-1.sock")
        (residents / f"{'1' * 20}-{unrelated.pid}.sock").write_text("junk")
        shown = run_cli("workers")
        assert shown.code == EXIT_OK and "waiting: 0" in shown.stdout, shown.stdout
        assert f"pid {unrelated.pid}" not in shown.stdout
        stopped = run_cli("workers", "stop")
        assert stopped.code == EXIT_OK, stopped.stderr
        assert "stopped 0 waiting workers" in stopped.stdout
        assert unrelated.poll() is None  # never signalled
        assert not (residents / f"{key}-{unrelated.pid}.sock").exists()
        assert not (residents / f"{key}-1.sock").exists()
        assert (residents / f"{'1' * 20}-{unrelated.pid}.sock").exists()  # not ours to remove
    finally:
        unrelated.kill()
        unrelated.wait()


def test_only_a_process_whose_command_line_shows_the_worker_is_taken_for_one(residents):
    assert not resident.is_worker(os.getpid(), residents)
    assert not resident.is_worker(1, residents)
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"])
    try:
        resident.stop(sleeper.pid)  # not a worker, not started by resident: left alone
        assert sleeper.poll() is None
    finally:
        sleeper.kill()
        sleeper.wait()


def _probe_package(folder: Path, value: int) -> None:
    (folder / "probe_code.py").write_text(
        f"import os\n\ndef run(payload):\n    return {{'value': {value}, 'pid': os.getpid()}}\n"
    )


def test_a_package_edited_in_place_is_not_served_by_workers_that_imported_it(
    residents, tmp_path, monkeypatch
):
    package = tmp_path / "site"
    package.mkdir()
    _probe_package(package, 1)
    monkeypatch.setenv("PYTHONPATH", str(package))
    pool = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        first = pool.run("probe_code:run", {}, "probe", None, timeout=60)
    finally:
        pool.close()
    assert first["value"] == 1
    _waiting(residents, 1)
    # Edited in place, as `pip install -e` or a patch would: same folder, same size.
    _probe_package(package, 2)
    later = time.time() + 5
    os.utime(package / "probe_code.py", (later, later))
    again = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        second = again.run("probe_code:run", {}, "probe", None, timeout=60)
    finally:
        again.close()
    assert second["value"] == 2
    assert second["pid"] != first["pid"]


def _mesh(path: Path, corners: int) -> None:
    """A closed mesh with 4 (a tetrahedron) or 8 (a box) vertices, written in place of
    ``path`` as a new file (as a product linked from the shared cache is)."""
    if corners == 4:
        text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    else:
        points = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
        text = "".join(f"v {x} {y} {z}\n" for x, y, z in points)
        text += "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\n"
        text += "f 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n"
    new = path.with_name(path.name + ".new")
    new.write_text(text)
    os.replace(new, path)


def test_a_product_published_again_within_the_same_second_is_compiled_anew(residents, tmp_path):
    products = tmp_path / "products"
    products.mkdir()
    mesh = products / "part.obj"
    second = int(time.time()) - 100
    _mesh(mesh, 4)
    os.utime(mesh, ns=(second * 10**9 + 200_000_000,) * 2)
    warm = {"folders": [str(products)]}
    pool = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        pool.run("mjcfbuild.steps.warm:run", warm, "warm", None, timeout=60)
        before = pool.run(VERTICES, {"file": str(mesh)}, "m", None, timeout=60)
    finally:
        pool.close()
    assert before["vertices"] == 4
    ended = time.time()
    # Another product of the same mesh, made by another folder's build in the same second,
    # is linked in its place: same name, same whole-second time, other content.
    _mesh(mesh, 8)
    os.utime(mesh, ns=(second * 10**9 + 700_000_000,) * 2)
    _waiting(residents, 1)
    _wait_for(lambda: int(time.time()) > int(ended))  # not the "same second" rule at work
    again = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        after = again.run(VERTICES, {"file": str(mesh)}, "m", None, timeout=60)
    finally:
        again.close()
    assert after["vertices"] == 8


def test_a_umask_077_build_writes_private_outputs_with_resident_workers(residents, tmp_path):
    arm = copy_example("arm", tmp_path)
    command = [sys.executable, "-m", "mjcfbuild", "build", "-q", "--no-check", "-j", "1"]

    def build(umask: int) -> None:
        process = subprocess.run(
            ["sh", "-c", f'umask {umask:03o} && exec "$@"', "sh", *command],
            cwd=arm,
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert process.returncode == EXIT_OK, process.stderr

    build(0o022)  # starts the worker that stays
    [worker] = _waiting(residents, 1)
    _edit_forearm(arm)
    (arm / "mjcf" / "example_arm.xml").unlink()
    before = {p: p.stat().st_ino for p in (arm / "mjcf").rglob("*") if p.is_file()}
    build(0o077)
    assert _waiting(residents, 1) == [worker]  # the same worker served it
    model = arm / "mjcf" / "example_arm.xml"
    assert model.stat().st_mode & 0o777 == 0o600
    # Every file the build made anew (a file kept keeps its mode, with any workers).
    written = [
        p
        for p in (arm / "mjcf").rglob("*")
        if p.is_file() and before.get(p) != p.stat().st_ino and p.stat().st_nlink == 1
    ]
    assert len(written) > 3
    assert [p for p in written if p.stat().st_mode & 0o077] == []


def test_a_build_runs_its_steps_at_its_own_nice_level(residents, tmp_path):
    step = [f"{STEPS}:echo"]
    script = (
        "import os, sys\n"
        "from pathlib import Path\n"
        "from mjcfbuild.engine.workers import WorkerPool\n"
        "pool = WorkerPool(1, Path.cwd(), Path(sys.argv[2]))\n"
        "try:\n"
        "    reply = pool.run(sys.argv[1], {}, 'echo', None, timeout=60)\n"
        "finally:\n"
        "    pool.close()\n"
        "print(reply['pid'], os.getpriority(os.PRIO_PROCESS, reply['pid']))\n"
    )

    def build(nice: int) -> tuple[int, int]:
        command = ["nice", "-n", str(nice), sys.executable, "-c", script, *step, str(tmp_path)]
        out = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stderr
        pid, level = out.stdout.split()
        return int(pid), int(level)

    _, level = build(10)
    assert level >= 10
    _waiting(residents, 1)
    # The worker takes on the build's level where it may (a privileged user), else it
    # leaves and the build starts one that inherits it: either way, the build's level.
    _, level = build(0)
    assert level == os.getpriority(os.PRIO_PROCESS, 0)


def test_a_socket_path_longer_than_a_socket_may_have_is_refused_with_the_reason(tmp_path):
    base = Path(tempfile.mkdtemp(prefix="mjr-", dir="/tmp"))
    try:
        # 78-80 characters passed the old check, and then workers failed to bind.
        too_long = base / ("t" * (79 - len(str(base)) - 1))
        assert len(str(too_long)) == 79
        assert resident.resident_dir({resident.DIR_VARIABLE: str(too_long)}) is None
        problem = resident.folder_problem(too_long)
        assert problem is not None and "too long for a socket path" in problem
        # The longest folder allowed holds the longest name a worker may use.
        room = resident._SUN_PATH - resident._NAME_LENGTH - 1
        fits = base / ("f" * (room - len(str(base)) - 1))
        assert len(str(fits)) == room
        assert resident.folder_problem(fits) is None
        listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        listener.bind(str(fits / ("k" * 20 + "-9999999.sock")))
        listener.close()
    finally:
        shutil.rmtree(base, ignore_errors=True)


def test_build_v_says_once_why_resident_workers_are_off(arm, tmp_path):
    # Only Jenkins says CI here (the suite itself may run in CI, with $CI set).
    quiet = {name: "" for name in (*resident.CI_VARIABLES, *resident.HOOK_VARIABLES)}
    env = {**quiet, resident.VARIABLE: "", "JENKINS_URL": "https://ci.example/"}
    result = run_cli("build", "-v", "--no-check", "-j", "1", cwd=arm, env=env)
    assert result.code == EXIT_OK, result.stderr
    assert result.stdout.count("resident workers are off") == 1
    assert "$JENKINS_URL is set" in result.stdout
    shared = tmp_path / "open"
    shared.mkdir()
    shared.chmod(0o755)
    env = {resident.VARIABLE: "60", resident.DIR_VARIABLE: str(shared)}
    result = run_cli("build", "-v", "--no-check", "-j", "1", cwd=arm, env=env)
    assert "resident workers are off" in result.stdout and str(shared) in result.stdout


def test_workers_notice_their_folder_is_gone_and_exit(residents, tmp_path):
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [orphan] = _waiting(residents, 1)
    shutil.rmtree(residents)
    _wait_for(lambda: _gone(orphan))


def test_junk_files_do_not_use_up_the_cap_which_counts_every_key_and_keeps_the_latest(
    residents, tmp_path, monkeypatch
):
    arm = copy_example("arm", tmp_path)

    def build(**env: str) -> None:
        (arm / "mjcf" / "example_arm.xml").unlink(missing_ok=True)
        result = run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm, env=env)
        assert result.code == EXIT_OK, result.stderr

    build()
    [first] = _waiting(residents, 1)
    key = _socket_of(residents, first).name.rpartition("-")[0]
    for number in range(2, 40):
        (residents / f"{key}-{number}.sock").write_text("not a worker")
    monkeypatch.setenv("MJCFBUILD_RESIDENT_MAX", "2")
    build()  # served by the first, which waits again: junk counts for nothing
    assert _waiting(residents, 1) == [first]
    build(OMP_NUM_THREADS="2")  # another key: a worker of its own, which waits too
    [second] = set(_waiting(residents, 2)) - {first}
    build(OMP_NUM_THREADS="3")  # a third key: one cap for all of this user's workers
    # The third's worker takes the place of the one that has waited longest: the first,
    # whose environment the user has not built in since.
    _wait_for(lambda: _gone(first))
    [third] = set(_waiting(residents, 2)) - {second}
    build(OMP_NUM_THREADS="3")  # the latest key's build finds its worker waiting
    assert set(_waiting(residents, 2)) == {second, third}


def test_workers_of_an_older_version_of_the_same_installation_end(residents, tmp_path):
    # A private installation of mjcfbuild, upgraded in place between two builds.
    site = tmp_path / "install"
    shutil.copytree(
        ROOT / "mjcfbuild", site / "mjcfbuild", ignore=shutil.ignore_patterns("__pycache__")
    )
    env = {"PYTHONPATH": f"{site}{os.pathsep}{ROOT}"}
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm, env=env).code == EXIT_OK
    [old] = _waiting(residents, 1)
    (site / "mjcfbuild" / "numbers.py").write_text(
        (site / "mjcfbuild" / "numbers.py").read_text() + "\n# upgraded\n"
    )
    (arm / "mjcf" / "example_arm.xml").unlink()
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm, env=env).code == EXIT_OK
    _wait_for(lambda: _gone(old))
    assert old not in resident.resident_pids(residents)
