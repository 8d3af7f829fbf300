"""``mjcfbuild build`` as a user runs it: output, summary line, exit codes, no tracebacks."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import EXIT_INPUT, EXIT_MANIFEST, EXIT_MODEL, EXIT_OK, EXIT_USAGE
from tests.conftest import run_cli, simple_manifest, two_link_urdf, write


def test_build_prints_progress_then_summary(cli, arm):
    result = cli("build", "-j", "2", cwd=arm)
    assert result.code == EXIT_OK, result.stderr
    assert "mesh base" in result.stdout and "check example_arm.xml" in result.stdout
    lines = result.stdout.strip().splitlines()
    assert lines.pop() == "  check: all checks pass (each check: `mjcfbuild check`)"
    if lines[-1].startswith("  slowest: "):  # only builds longer than two seconds say it
        lines.pop()
    assert lines[-1].startswith("mjcfbuild: built example_arm.xml: 13 run, 0 up to date")
    again = cli("build", cwd=arm)
    summary, check = again.stdout.splitlines()  # the no-op says what the build said
    assert "0 run, 13 up to date" in summary and check == lines_after(result.stdout)
    unchecked = cli("build", "--no-check", cwd=arm)
    assert unchecked.stdout.splitlines()[-1] == (
        "  check: not run (--no-check); `mjcfbuild check` runs it"
    )


def lines_after(stdout: str) -> str:
    """The check's line of a build's output."""
    return next(line for line in stdout.splitlines() if line.startswith("  check: "))


def test_manifest_path_from_another_folder(cli, arm, tmp_path):
    result = cli("build", str(arm / "robot.yaml"), "-q", cwd=tmp_path)
    assert result.code == EXIT_OK and result.stdout == ""
    assert (arm / "mjcf" / "example_arm.xml").exists()


def test_manifest_error_has_path_line_and_no_traceback(cli, tmp_path):
    folder = tmp_path / "robot"
    write(folder / "robot.yaml", "name: r\nsource:\n  urdf: r.urdf\n  bogus: 1\n")
    result = cli("build", "robot/robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_MANIFEST
    assert result.stderr.strip() == (
        "mjcfbuild: error: robot/robot.yaml:4:3: source.bogus: unknown key 'bogus'; "
        "allowed keys: args, description, read_outside, urdf, xacro"
    )
    assert "Traceback" not in result.stderr


def test_missing_source_file(cli, tmp_path):
    simple_manifest(tmp_path)
    result = cli("build", cwd=tmp_path)
    assert result.code == EXIT_INPUT
    assert "robot.urdf: source file not found" in result.stderr


def test_urdf_error_points_at_the_urdf_line(cli, tmp_path):
    simple_manifest(tmp_path)
    write(
        tmp_path / "robot.urdf",
        two_link_urdf().replace('<child link="arm"/>', '<child link="arn"/>'),
    )
    result = cli("build", cwd=tmp_path)
    assert result.code == EXIT_INPUT
    assert (
        "robot.urdf:11: joint 'hinge' refers to link 'arn', which does not exist" in result.stderr
    )
    assert "did you mean 'arm'?" in result.stderr
    assert "mjcfbuild: failed robot.xml" in result.stdout


def test_build_failure_in_a_worker_is_reported_with_its_file(cli, arm):
    (arm / "meshes" / "finger.stl").write_bytes(b"garbage")
    result = cli("build", cwd=arm)
    assert result.code == EXIT_INPUT
    # at the URDF line naming the mesh, then the mesh's own file
    assert "mjcfbuild: error: urdf/finger.xacro:13: meshes/finger.stl: " in result.stderr
    assert "Traceback" not in result.stderr


def test_bad_jobs_argument_is_a_usage_error(cli, arm):
    result = cli("build", "-j", "0", cwd=arm)
    assert result.code == EXIT_USAGE


def test_version_and_help(cli):
    assert cli("--version").stdout.startswith("mjcfbuild ")
    help_text = cli("--help").stdout
    for command in ("build", "convert", "init", "schema"):
        assert command in help_text
    assert "exit codes:" in help_text


def test_fail_on_change_fails_until_created_and_changed_files_are_added(cli, arm):
    import subprocess

    def git(*args):
        subprocess.run(["git", *args], cwd=arm, check=True, capture_output=True)

    git("init", "-q")
    created = cli("build", "--no-check", "--fail-on-change", cwd=arm)
    assert created.code == 6, created.stderr
    assert "files were created: mjcf/example_arm.xml, mjcf/scene.xml" in created.stderr
    assert "git add them" in created.stderr
    # Nothing rebuilt, but the model is still not added: the no-op fails too.
    again = cli("build", "--no-check", "--fail-on-change", cwd=arm)
    assert again.code == 6 and "0 run" in again.stdout, again.stderr
    assert "files git does not track: mjcf/example_arm.xml" in again.stderr
    assert "created" not in again.stderr  # this build created nothing
    git("add", "-A")
    assert cli("build", "--no-check", "--fail-on-change", cwd=arm).code == 0
    # A hand edit git does not hold stops the build and stays; checked out again, the model
    # is what git has: nothing to add.
    model = arm / "mjcf" / "example_arm.xml"
    built = model.read_bytes()
    model.write_text(model.read_text().replace("<mujoco", "<!-- mine -->\n<mujoco", 1))
    kept = cli("build", "--no-check", "--fail-on-change", cwd=arm)
    assert kept.code == 7 and "git has no commit of the edit" in kept.stderr, kept.stderr
    git("checkout", "--", "mjcf/example_arm.xml")
    assert model.read_bytes() == built
    assert cli("build", "--no-check", "--fail-on-change", cwd=arm).code == 0
    # After a clean, the build writes the committed files again as they are: nothing to add.
    assert cli("clean", "-q", cwd=arm).code == 0
    rebuilt = cli("build", "--no-check", "--fail-on-change", cwd=arm)
    assert rebuilt.code == 0, rebuilt.stderr
    limits = arm / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    changed = cli("build", "--no-check", "--fail-on-change", "-q", cwd=arm)
    assert changed.code == 6
    assert "files were changed: mjcf/example_arm.xml" in changed.stderr
    assert "created" not in changed.stderr
    # An asset the model stops using is removed: its removal must be staged too, or the
    # commit keeps it (a fresh clone then found it, "not written by mjcfbuild").
    git("add", "-A")
    xacro = arm / "urdf" / "arm.urdf.xacro"
    xacro.write_text(
        xacro.read_text().replace(
            '<mesh filename="package://arm_description/meshes/base.stl"/>',
            '<cylinder radius="0.08" length="0.1"/>',
        )
    )
    git("add", "urdf")
    removed = cli("build", "--no-check", "--fail-on-change", "-q", cwd=arm)
    assert removed.code == 6
    assert "files were removed that git still has: mjcf/assets/base.obj" in removed.stderr
    git("add", "mjcf/example_arm.xml")  # not the removal: the no-op says so again
    again = cli("build", "--no-check", "--fail-on-change", "-q", cwd=arm)
    assert again.code == 6 and "mjcf/assets/base.obj" in again.stderr, again.stderr
    git("add", "mjcf/assets/base.obj")
    assert cli("build", "--no-check", "--fail-on-change", cwd=arm).code == 0


@pytest.mark.slow
def test_a_chain_as_deep_as_mujoco_reads_builds(tmp_path):
    # 496 nested bodies: past lxml's 256 and Python's recursion limit, within MuJoCo's.
    import mujoco

    from bench.deep_chain import snake_urdf
    from mjcfbuild.mjcf.depth import MAX_BODY_DEPTH

    write(tmp_path / "snake.urdf", snake_urdf(MAX_BODY_DEPTH))
    manifest = simple_manifest(tmp_path, "urdf: snake.urdf")
    result = run_cli("build", "-q", "--no-check", str(manifest))
    assert result.code == EXIT_OK, result.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "robot.xml"))
    assert model.nbody == MAX_BODY_DEPTH + 1 and model.njnt == MAX_BODY_DEPTH - 1


def test_a_2000_link_chain_stops_at_plan_with_mujocos_limit(tmp_path):
    from bench.deep_chain import snake_urdf

    text = snake_urdf(2000)
    write(tmp_path / "snake.urdf", text)
    manifest = simple_manifest(tmp_path, "urdf: snake.urdf")
    result = run_cli("build", str(manifest))
    assert result.code == EXIT_MODEL, result.stderr
    [error] = [line for line in result.stderr.splitlines() if "error" in line]
    line = text.splitlines().index(
        '  <joint name="j496" type="revolute"><parent link="l495"/><child link="l496"/>'
    )
    assert f"snake.urdf:{line + 1}: the kinematic tree nests bodies 2000 deep" in error
    assert "MuJoCo reads at most 496" in error and "not a fault in the file" in error
    assert "Traceback" not in result.stderr and "self-collision" not in result.stdout
    assert not (tmp_path / "mjcf" / "robot.xml").exists()


def test_a_timeout_from_the_environment_that_is_not_seconds_is_refused(tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    manifest = simple_manifest(tmp_path)
    result = run_cli("build", str(manifest), env={"MJCFBUILD_TIMEOUT": "-5"})
    assert result.code == EXIT_USAGE
    assert result.stderr.startswith("mjcfbuild: error: MJCFBUILD_TIMEOUT=-5: must be more than 0")


def test_files_are_named_from_the_current_folder_in_warnings_and_the_check(tmp_path):
    """Errors named files from the current folder; warnings and check's lines from the
    manifest's, which from elsewhere named files that are not there."""
    robot = tmp_path / "robot"
    write(
        robot / "w.urdf",
        '<robot name="w"><link name="base"><visual><geometry><box size="0 0 0"/></geometry>'
        "</visual></link></robot>",
    )
    write(robot / "robot.yaml", "name: w\nsource: {urdf: w.urdf}\n")
    for _ in range(2):  # the build, then its no-op
        result = run_cli("build", "robot/robot.yaml", cwd=tmp_path)
        assert result.code == EXIT_OK, result.stderr
        assert "mjcfbuild: warning: robot/w.urdf:1: link 'base' visual 0" in result.stderr
    checked = run_cli("check", "robot/robot.yaml", cwd=tmp_path)
    assert checked.stdout.splitlines()[0] == "mjcfbuild check: robot/mjcf/w.xml"
    assert "  report: robot/mjcf/report/report.md" in checked.stdout.splitlines()


def test_fail_on_change_outside_git_does_not_ask_for_git_add(cli, arm):
    created = cli("build", "--no-check", "--fail-on-change", cwd=arm)
    assert created.code == 6
    assert "files were created: mjcf/example_arm.xml" in created.stderr
    assert "git add" not in created.stderr and "not in a git work tree" in created.stderr
    assert cli("build", "--no-check", "--fail-on-change", cwd=arm).code == 0  # nothing new
