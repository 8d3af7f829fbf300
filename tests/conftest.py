"""Shared fixtures: copies of the examples, running the real command line, small URDFs."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def pytest_configure(config):
    """Keep the tests' shared cache (validated manifests, mesh products) out of the user's,
    and their workers to themselves."""
    import tempfile

    # Under pytest-xdist (CI runs ``-n 2``) each worker is a process of its own that inherits
    # the controller's environment: it makes its own cache, so no test sees a cache entry that a
    # test running at the same time in the other worker is writing.
    # (A variable of its own to mark the controller's cache would be an MJCFBUILD_* variable,
    # which the no-op stamp records, so the folder's name marks it.)
    worker = os.environ.get("PYTEST_XDIST_WORKER")
    prefix = f"mjcfbuild-test-cache-{worker}-" if worker else "mjcfbuild-test-cache-"
    inherited = Path(os.environ.get("MJCFBUILD_CACHE_DIR", "")).name
    if (
        worker
        and inherited.startswith("mjcfbuild-test-cache-")
        and not inherited.startswith(prefix)
    ):
        del os.environ["MJCFBUILD_CACHE_DIR"]
    if "MJCFBUILD_CACHE_DIR" not in os.environ:
        os.environ["MJCFBUILD_CACHE_DIR"] = tempfile.mkdtemp(prefix=prefix)
        config._mjcfbuild_cache = os.environ["MJCFBUILD_CACHE_DIR"]
    # Every build starts its own workers: a worker that stayed after one test's build would
    # serve the next test's. tests/engine/test_resident.py turns them on where it tests them.
    os.environ["MJCFBUILD_RESIDENT_WORKERS"] = "0"
    # One task at a time unless a test asks for more (-j, jobs=). The suite already keeps
    # every core busy (README's command runs two tests at once on two cores), and a build's
    # second job is a head start for its model: a worker that imports MuJoCo and processes the
    # meshes beside the first. Here it only doubled that work (a third of the suite's time).
    # The outputs do not depend on -j (tests/engine/test_determinism.py); the tests of the
    # parallel engine, its warm-ups and its interruptions pass -j 2 themselves.
    os.environ.setdefault("MJCFBUILD_JOBS", "1")
    if hasattr(config.option, "loadscopereorder"):  # pytest-xdist: keep the order set below
        config.option.loadscopereorder = False
    if not worker:
        compile_bytecode_once()
    from tests.fuzzing import load_profile

    load_profile()  # property tests: deterministic unless MJCFBUILD_FUZZ asks for a long run


def compile_bytecode_once() -> None:
    """Write the bytecode of mjcfbuild and the tests, once, before the workers start.

    The tests start the command line two thousand times. An editable install ships no bytecode,
    and where ``PYTHONDONTWRITEBYTECODE`` is set (as on the project's machines) each of those
    processes compiled every module it imported afresh: a quarter of a failed build's time.
    A process still reads bytecode that is there, and Python checks it against the source."""
    import compileall

    for package in ("mjcfbuild", "tests"):
        compileall.compile_dir(ROOT / package, quiet=2, workers=1)


def pytest_unconfigure(config):
    """Remove the cache this session made (a session of the page tests leaves 5 MB in it)."""
    made = getattr(config, "_mjcfbuild_cache", None)
    if made:
        shutil.rmtree(made, ignore_errors=True)


QUICK_LANE = Path(__file__).with_name("quick_lane.txt")
FILE_SECONDS = Path(__file__).with_name("file_seconds.txt")


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Mark the tests of the quick lane (``pytest -m quick``) before ``-m`` selects, and run
    the slowest test files first."""
    lane = set(QUICK_LANE.read_text().splitlines()) if QUICK_LANE.is_file() else set()
    for item in items:
        if item.nodeid in lane:
            item.add_marker(pytest.mark.quick)
    # pytest-xdist hands whole files to its workers in this order (its own reordering, by
    # the number of tests in a file, is turned off in pytest_configure): slowest first, so
    # the run does not end with one worker alone on a long file (the MuJoCo Warp tests: six
    # tests, a minute and a half). A file not in the list (a new one) comes last; the order
    # of the tests in a file stays as written.
    seconds = file_seconds()
    items.sort(key=lambda item: -seconds.get(item.nodeid.split("::")[0], 0.0))


def file_seconds() -> dict[str, float]:
    """Each test file's seconds in a measured full run (``bench/quick_lane.py`` writes them)."""
    if not FILE_SECONDS.is_file():
        return {}
    measured = {}
    for line in FILE_SECONDS.read_text().splitlines():
        spent, _, path = line.partition(" ")
        measured[path] = float(spent)
    return measured


@dataclass
class CliResult:
    """What a run of the mjcfbuild command printed and returned."""

    code: int
    stdout: str
    stderr: str


def run_cli(*args: str, cwd: Path | None = None, stdin: str | None = None, env=None) -> CliResult:
    """Run ``python -m mjcfbuild`` as a user would, in a separate process."""
    environment = dict(os.environ)
    environment.update(env or {})
    process = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", *args],
        cwd=cwd,
        input=stdin,
        capture_output=True,
        text=True,
        env=environment,
        timeout=600,
        preexec_fn=sigint_at_default,
    )
    return CliResult(process.returncode, process.stdout, process.stderr)


def sigint_at_default() -> None:
    """Give SIGINT its default action in a process about to start a command: what a terminal
    gives a command, whether this test run inherited SIGINT ignored (started in the background
    by a script) or not, which the command would keep (mjcfbuild/interrupts.py)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def file_clock_past(folder: Path, ns: int) -> None:
    """Return once a file changed in ``folder`` gets a status-change time later than ``ns``.

    The kernel stamps files from a clock that ticks every few milliseconds: a test whose next
    change must carry a later time than an earlier one waits for that tick (a loop of
    ``utime`` calls on a probe file), never for a fixed time."""
    probe = folder / ".file-clock-probe"
    probe.write_bytes(b"")
    while os.stat(probe).st_ctime_ns <= ns:
        os.utime(probe)
    probe.unlink()


@pytest.fixture
def cli():
    """The :func:`run_cli` function."""
    return run_cli


def copy_example(name: str, destination: Path) -> Path:
    """A private copy of ``examples/<name>`` (with its sibling examples, which some refer to),
    without build outputs; the example's folder."""
    target = destination / "examples"
    shutil.copytree(EXAMPLES, target, ignore=shutil.ignore_patterns("mjcf", "__pycache__"))
    file_clock_past_changes(target)
    return target / name


def file_clock_past_changes(folder: Path) -> None:
    """Return once the file clock is past the last change below ``folder``: a build started
    now finds no input changed since it began (one that does leaves no no-op stamp,
    mjcfbuild.engine.stamp), as when a person or a script's next command builds it."""
    from mjcfbuild.filesig import file_clock_ns

    newest = max(os.stat(path).st_ctime_ns for path in [folder, *folder.rglob("*")])
    while file_clock_ns() <= newest:
        time.sleep(0.001)


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    """A copy of the example arm."""
    return copy_example("arm", tmp_path)


@pytest.fixture(scope="module")
def built_examples(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The examples with the arm built by ``mjcfbuild build -q --no-check``, once per test
    module (in a cache of its own); tests take copies of it (:func:`built_arm`), never it."""
    folder = tmp_path_factory.mktemp("built-arm")
    arm = copy_example("arm", folder)
    cache = {"MJCFBUILD_CACHE_DIR": str(folder / "cache")}
    result = run_cli("build", "-q", "--no-check", cwd=arm, env=cache)
    assert result.code == 0, result.stderr
    return folder / "examples"


@pytest.fixture
def built_arm(built_examples: Path, tmp_path: Path) -> Path:
    """A private copy of the example arm with the outputs ``build -q --no-check`` wrote, for
    tests of what is done with a built folder (clean). The build's records name the files it
    wrote relative to the output folder, but its database names them by absolute path: a
    build in the copy runs every task again, as in a moved folder."""
    shutil.copytree(built_examples, tmp_path / "examples", symlinks=True)
    return tmp_path / "examples" / "arm"


@pytest.fixture
def demo(tmp_path: Path) -> Path:
    """A copy of the reference converter's demo robot."""
    return copy_example("reference_demo", tmp_path)


def write(path: Path, text: str) -> Path:
    """Write ``text`` to ``path`` (creating folders) and return the path."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


INERTIA = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def two_link_urdf(extra: str = "", joint_type: str = "revolute") -> str:
    """A small valid URDF: base and one moving link, plus ``extra`` elements."""
    return f"""<?xml version="1.0" encoding="utf-8"?>
<robot name="two_link">
  <link name="base">{INERTIA}
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="arm">{INERTIA}
    <visual><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.03" length="0.5"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material></visual>
    <collision><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.03" length="0.5"/></geometry></collision>
  </link>
  <joint name="hinge" type="{joint_type}">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 0.1" rpy="0 0 0.3"/>
    <axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  {extra}
</robot>
"""


def simple_manifest(folder: Path, source_line: str = "urdf: robot.urdf", extra: str = "") -> Path:
    """A manifest in ``folder`` building ``robot.urdf`` into ``mjcf/``."""
    return write(folder / "robot.yaml", f"name: robot\nsource:\n  {source_line}\n{extra}")
