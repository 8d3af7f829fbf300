"""Real builds killed (kill -9) or interrupted (Ctrl-C) at chosen moments recover: the next
build finishes, its outputs are byte-identical to a clean build's, and converted meshes and
decompositions that were finished are not redone. An interrupted build exits 130 saying so in
one line, also where its KeyboardInterrupt was lost; one started with SIGINT ignored keeps
ignoring it. SIGTERM (``kill``, a CI runner cancelling a job) stops a build as Ctrl-C does,
with exit 143."""

from __future__ import annotations

import filecmp
import os
import re
import subprocess
import sys

import pytest

from mjcfbuild.errors import EXIT_INTERRUPTED, EXIT_TERMINATED
from tests.conftest import CliResult, copy_example, run_cli

pytestmark = pytest.mark.slow

RULES = "collision:\n  rules:\n    - links: [upper_arm_link]\n      policy: decompose\n"
MOMENTS = [
    ("mesh", "kill"),
    ("mesh", "interrupt"),
    ("decompose", "kill"),
    ("decompose", "interrupt"),
    ("assemble", "kill"),
    ("assemble", "interrupt"),
    ("write:example_arm.xml", "kill"),
    ("write:scene.xml", "kill"),
    # In the build process: between doit's two stages, before the report and before the
    # no-op stamp; "swallowed" loses the KeyboardInterrupt, as a finalizer would.
    ("stages", "interrupt"),
    ("stages", "interrupt-swallowed"),
    ("report", "interrupt-swallowed"),
    ("stamp", "interrupt-swallowed"),
    # SIGTERM, as `kill` or a CI runner cancelling the job sends it: handled as Ctrl-C.
    ("assemble", "terminate"),
    ("stages", "terminate"),
]


def arm_with_decomposition(folder):
    arm = copy_example("arm", folder)
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + RULES)
    return arm


def outputs(folder):
    return sorted(
        str(p.relative_to(folder))
        for p in folder.rglob("*")
        if p.is_file() and not {".mjcfbuild", "report"} & set(p.relative_to(folder).parts)
    )


@pytest.fixture(scope="module")
def clean_build(tmp_path_factory):
    arm = arm_with_decomposition(tmp_path_factory.mktemp("clean"))
    result = run_cli(
        "build", "-q", "-j", "2", cwd=arm, env={"MJCFBUILD_CACHE_DIR": str(arm.parent / "cache")}
    )
    assert result.code == 0, result.stderr
    return arm / "mjcf"


@pytest.mark.parametrize(("point", "action"), MOMENTS, ids=[f"{p}-{a}" for p, a in MOMENTS])
def test_interrupted_build_recovers(tmp_path, clean_build, point, action):
    arm = arm_with_decomposition(tmp_path)
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    stopped = run_cli(
        "build", "-j", "2", cwd=arm, env={**env, "MJCFBUILD_FAILPOINT": f"{point}:{action}"}
    )
    if action.startswith("interrupt"):
        assert_interrupted(stopped)
    elif action == "terminate":
        assert_interrupted(stopped, EXIT_TERMINATED)
    else:
        assert stopped.code == -9, stopped.stdout + stopped.stderr
    assert_recovers(arm, env, stopped, clean_build)


def test_a_build_started_with_sigint_ignored_keeps_ignoring_it(tmp_path, clean_build):
    # A shell script starts `mjcfbuild build &` with SIGINT ignored, so that Ctrl-C at the
    # terminal stops its foreground command and leaves the build running: the build keeps to
    # that (as make and Python do), runs to its end and says so.
    arm = arm_with_decomposition(tmp_path)
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    command = [sys.executable, "-m", "mjcfbuild", "build", "-j", "2"]
    process = subprocess.run(
        ["sh", "-c", 'trap "" INT; exec "$0" "$@"', *command],
        cwd=arm,
        env={**os.environ, **env, "MJCFBUILD_FAILPOINT": "mesh:interrupt"},
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert process.returncode == 0, process.stdout + process.stderr
    assert "mjcfbuild: built" in process.stdout and "interrupted" not in process.stderr
    built = arm / "mjcf"
    assert outputs(built) == outputs(clean_build)
    _, mismatch, errors = filecmp.cmpfiles(built, clean_build, outputs(built), shallow=False)
    assert mismatch == [] and errors == []


def assert_interrupted(stopped: CliResult, code: int = EXIT_INTERRUPTED) -> None:
    """The build stopped with the interruption's code (130 for Ctrl-C, 143 for SIGTERM) and
    one line, and claimed nothing."""
    assert stopped.code == code, stopped.stdout + stopped.stderr
    assert stopped.stderr.splitlines() == ["mjcfbuild: interrupted"], stopped.stderr
    assert "mjcfbuild: built" not in stopped.stdout


def assert_recovers(arm, env: dict[str, str], stopped: CliResult, clean_build) -> None:
    """The next build finishes with a clean build's outputs, redoing no finished work."""
    again = run_cli("build", "-j", "2", cwd=arm, env=env)
    assert again.code == 0, again.stdout + again.stderr
    # Work finished before the stop is not redone: it is up to date or comes from the cache.
    redone = [
        line
        for line in again.stdout.splitlines()
        if re.search(r"\] (mesh|decompose) ", line) and "from cache" not in line
    ]
    finished_before = re.findall(r"\] ((?:mesh|decompose) \S+)", stopped.stdout)
    for title in finished_before:
        assert not any(title in line for line in redone), (title, again.stdout)

    built = arm / "mjcf"
    assert not list(built.rglob("*.mjcfbuild-tmp"))
    assert outputs(built) == outputs(clean_build)
    _, mismatch, errors = filecmp.cmpfiles(built, clean_build, outputs(built), shallow=False)
    assert mismatch == [] and errors == []


def test_a_build_stopped_by_sigterm_keeps_its_finished_tasks(tmp_path):
    # The next build runs with an empty cache of its own: a mesh it converted again could not
    # hide behind "from cache". Every mesh finished before the assembly, where SIGTERM comes.
    arm = copy_example("arm", tmp_path)
    stopped = run_cli(
        "build",
        "-j",
        "2",
        cwd=arm,
        env={
            "MJCFBUILD_CACHE_DIR": str(tmp_path / "cache"),
            "MJCFBUILD_FAILPOINT": "assemble:terminate",
        },
    )
    assert_interrupted(stopped, EXIT_TERMINATED)
    assert re.findall(r"\] mesh \S+", stopped.stdout), stopped.stdout
    again = run_cli("build", "-j", "2", cwd=arm, env={"MJCFBUILD_CACHE_DIR": str(tmp_path / "c2")})
    assert again.code == 0, again.stdout + again.stderr
    assert not re.findall(r"\] (expand|plan|mesh) ", again.stdout), again.stdout
    assert "assemble" in again.stdout and not list(arm.rglob("*.mjcfbuild-tmp"))


def test_a_step_running_in_the_build_process_finishes_before_the_build_ends(tmp_path):
    # A URDF is read in the build process, in one of doit's threads, which the interrupted
    # stage leaves running: the step (here busy for two more seconds) writes its files before
    # the build lets go of the folder, not after it or half-way as the process ends.
    quadruped = copy_example("quadruped", tmp_path)
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    stopped = run_cli(
        "build", "-j", "2", cwd=quadruped, env={**env, "MJCFBUILD_FAILPOINT": "expand:interrupt"}
    )
    assert_interrupted(stopped)
    state = quadruped / "mjcf" / ".mjcfbuild"
    assert (state / "source.urdf").read_text().rstrip().endswith("</robot>")
    assert (state / "source.origins.json").is_file()
    assert not list(quadruped.rglob("*.mjcfbuild-tmp"))

    again = run_cli("build", "-q", "-j", "2", "--no-check", cwd=quadruped, env=env)
    assert again.code == 0, again.stdout + again.stderr
