"""``mjcfbuild check``: any URDF/MJCF pair, the build's check task, --up-to-date, the report."""

from __future__ import annotations

import shutil

import numpy as np
from PIL import Image

import mjcfbuild
from mjcfbuild.check.results import CheckResults
from mjcfbuild.errors import EXIT_CHECK, EXIT_OK
from tests.conftest import copy_example, run_cli, write

URDF = """<robot name="pendulum">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="0 0 -0.5"/><mass value="1"/>
    <inertia ixx="0.02" iyy="0.02" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="swing" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""

# Written by hand: the body frame sits at the centre of mass, not at the joint.
MJCF = """<mujoco><compiler angle="radian"/><worldbody>
  <site name="base"/>
  <body name="arm" pos="0 0 1">
    <joint name="swing" axis="0 1 0" range="-1 1"/>
    <inertial pos="0 0 -0.5" mass="1" diaginertia="0.02 0.02 0.001"/>
    <geom type="capsule" fromto="0 0 0 0 0 -1" size="0.02" contype="0" conaffinity="0"/>
  </body>
</worldbody></mujoco>"""


# A position servo on the joint and a home keyframe it holds, for MJCF.
DRIVEN = """</worldbody>
  <actuator><position name="swing" joint="swing" kp="200" kv="20" ctrlrange="-1 1"/></actuator>
  <keyframe><key name="home" qpos="0" ctrl="0"/></keyframe>"""


def test_any_urdf_against_a_hand_written_mjcf(tmp_path):
    write(tmp_path / "p.urdf", URDF)
    write(tmp_path / "p.xml", MJCF)
    result = run_cli("check", "--urdf", "p.urdf", "--mjcf", "p.xml", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    # Without an actuator or a home keyframe, passing proves less: the verdict says what.
    lines = result.stdout.splitlines()
    assert "mjcfbuild: check passed" not in lines
    assert lines[-1] == (
        "mjcfbuild: checks pass, but 1 actuation problem (joint 'swing' has no actuator): a "
        "controller cannot drive every joint; the hold and stand tests were not run: the "
        "model has no home keyframe"
    )
    driven = next(line for line in lines if "every moving joint driven" in line)
    assert driven.endswith("1 problem (not required of a model mjcfbuild did not build)")
    write(tmp_path / "driven.xml", MJCF.replace("</worldbody>", DRIVEN))
    result = run_cli("check", "--urdf", "p.urdf", "--mjcf", "driven.xml", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    assert result.stdout.splitlines()[-1] == "mjcfbuild: check passed"
    write(tmp_path / "bad.xml", MJCF.replace('mass="1"', 'mass="2"'))
    result = run_cli("check", "--urdf", "p.urdf", "--mjcf", "bad.xml", cwd=tmp_path)
    assert result.code == EXIT_CHECK
    assert "body 'arm': mass 1 in the URDF (links arm), 2 in the model" in result.stderr


def test_build_ends_with_the_check_and_a_report_with_pictures(tmp_path):
    arm = copy_example("arm", tmp_path)
    result = mjcfbuild.build(arm / "robot.yaml", jobs=2)
    assert "check" in result.ran and "previews" in result.ran
    report = arm / "mjcf" / "report"
    text = (report / "report.md").read_text()
    assert "Result: all checks pass." in text
    assert "![three quarter visual](previews/three_quarter_visual.png)" in text
    images = {p.stem: np.asarray(Image.open(p)) for p in (report / "previews").glob("*.png")}
    assert sorted(images) == [
        "closeup_collision",
        "closeup_visual",
        "side_collision",
        "side_visual",
        "three_quarter_collision",
        "three_quarter_visual",
        "top_visual",
    ]
    for name, pixels in images.items():
        if "collision" not in name:
            continue
        # collision geometry is drawn orange; floor and sky are blue
        robot = pixels[..., 0].astype(int) > pixels[..., 2].astype(int) + 60
        assert 0.05 < robot.mean() < 0.9, name  # the robot is there, not everywhere
        rows, columns = np.nonzero(robot)
        spans = ((rows.max() - rows.min() + 1) / robot.shape[0],
                 (columns.max() - columns.min() + 1) / robot.shape[1])  # fmt: skip
        if name != "closeup_collision":  # a close-up crops the arm it looks along
            assert max(spans) > 0.8, (name, spans)  # the robot fills the frame
            assert rows.min() > 0 and columns.min() > 0, name  # and is inside it
    assert not np.array_equal(images["three_quarter_visual"], images["side_visual"])
    assert not np.array_equal(images["three_quarter_visual"], images["three_quarter_collision"])
    assert (report / ".gitignore").read_text().endswith("*\n")


def test_no_check_skips_it(tmp_path):
    arm = copy_example("arm", tmp_path)
    result = run_cli("build", "--no-check", "-q", cwd=arm)
    assert result.code == EXIT_OK
    assert not (arm / "mjcf" / "report" / "previews").exists()


def test_up_to_date_with_and_without_the_build_database(tmp_path):
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == EXIT_OK
    current = run_cli("check", "--up-to-date", cwd=arm)
    assert current.code == EXIT_OK
    # The model is current; its report is not (a build without the check, or one cut short
    # after the model): said, not hidden.
    assert "mjcf is up to date (its report is not: check example_arm.xml" in current.stdout
    limits = arm / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    stale = run_cli("check", "--up-to-date", cwd=arm)
    assert stale.code == EXIT_CHECK
    assert "input changed: config/joint_limits.yaml" in stale.stderr
    # A fresh clone: committed outputs, no database. Rebuilt aside and compared.
    shutil.rmtree(arm / "mjcf" / ".mjcfbuild")
    stale = run_cli("check", "--up-to-date", cwd=arm)
    assert stale.code == EXIT_CHECK
    assert "mjcf/example_arm.xml differs from what its inputs build" in stale.stderr
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == EXIT_OK
    shutil.rmtree(arm / "mjcf" / ".mjcfbuild")
    assert run_cli("check", "--up-to-date", cwd=arm).code == EXIT_OK


def test_up_to_date_names_each_manifest(tmp_path):
    examples = copy_example("arm", tmp_path).parent
    for name in ("arm", "reference_demo"):
        assert run_cli("build", "-q", "--no-check", cwd=examples / name).code == EXIT_OK
    result = run_cli(
        "check", "--up-to-date", "arm/robot.yaml", "reference_demo/robot.yaml", cwd=examples
    )
    assert result.code == EXIT_OK, result.stderr
    assert "arm/robot.yaml: mjcf is up to date" in result.stdout
    assert "reference_demo/robot.yaml: mjcf is up to date" in result.stdout


def test_a_xacro_urdf_is_expanded(tmp_path):
    """As `convert -u` does: `check --urdf robot.urdf.xacro` is not "4 root links"."""
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == EXIT_OK
    result = run_cli(
        "check",
        "--urdf",
        "urdf/arm.urdf.xacro",
        "--mjcf",
        "mjcf/example_arm.xml",
        cwd=arm,
        env={"ROS_PACKAGE_PATH": str(arm)},
    )
    assert result.code == EXIT_OK, result.stdout + result.stderr


# A hand-written model of a 3-link arm, with MuJoCo's 6 significant digits.
ROUNDED_URDF = """<robot name="arm">
  <link name="base"/>
  <link name="upper"><inertial><mass value="0.255"/>
    <inertia ixx="3.6800049e-05" iyy="3.6800049e-05" izz="1.2e-05" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="lower"><inertial><origin xyz="0 0 -0.1"/><mass value="0.255"/>
    <inertia ixx="3.6800049e-05" iyy="3.6800049e-05" izz="1.2e-05" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tool"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 1"/><axis xyz="0 1 0"/><limit lower="-1.972222222" upper="1.972222222" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 -0.2"/><axis xyz="0 1 0"/><limit lower="-2.356194490" upper="2.356194490" effort="1" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="lower"/><child link="tool"/><origin xyz="0 0 -0.2"/></joint>
</robot>"""

ROUNDED_MJCF = """<mujoco><compiler angle="radian"/><worldbody>
  <site name="base"/>
  <body name="upper" pos="0 0 1">
    <joint name="shoulder" axis="0 1 0" range="-1.97222 1.97222"/>
    <inertial pos="0 0 0" mass="0.255" diaginertia="3.68001e-05 3.68001e-05 1.2e-05"/>
    <body name="lower" pos="0 0 -0.2">
      <joint name="elbow" axis="0 1 0" range="-2.35619 2.35619"/>
      <inertial pos="0 0 -0.1" mass="0.255" diaginertia="3.68001e-05 3.68001e-05 1.2e-05"/>
      TOOL
    </body>
  </body>
</worldbody></mujoco>"""


def test_rounding_of_a_hand_written_model_is_not_a_failure(tmp_path):
    write(tmp_path / "arm.urdf", ROUNDED_URDF)
    write(tmp_path / "arm.xml", ROUNDED_MJCF.replace("TOOL", '<site name="tool" pos="0 0 -0.2"/>'))
    result = run_cli("check", "--urdf", "arm.urdf", "--mjcf", "arm.xml", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    # --tolerance governs every quantity: asked for 1e-7, the ranges' rounding shows.
    strict = run_cli(
        "check", "--urdf", "arm.urdf", "--mjcf", "arm.xml", "--tolerance", "1e-7", cwd=tmp_path
    )
    assert strict.code == EXIT_CHECK
    assert "joint 'shoulder': range (-1.97222, 1.97222) in the URDF" in strict.stderr


def test_structural_findings_come_first(tmp_path):
    write(tmp_path / "arm.urdf", ROUNDED_URDF)
    wrong = (
        ROUNDED_MJCF.replace("TOOL", "")
        .replace('pos="0 0 -0.1" mass="0.255"', 'pos="0 0 -0.1" mass="0.085"')
        .replace('axis="0 1 0" range="-2.35619', 'axis="0 0.9 0.1" range="-2.35619')
    )
    write(tmp_path / "arm.xml", wrong)
    result = run_cli("check", "--urdf", "arm.urdf", "--mjcf", "arm.xml", cwd=tmp_path)
    assert result.code == EXIT_CHECK
    failures = [
        line.removeprefix("mjcfbuild: check failed: ")
        for line in result.stderr.splitlines()
        if line.startswith("mjcfbuild: check failed: ")
    ]
    assert failures[0] == "link 'tool' has no body or site of its name in the model"
    assert failures[1].startswith("body 'lower': mass 0.255 in the URDF")
    assert "0.085 in the model" in failures[1]
    assert any("joint 'elbow': axis" in f for f in failures[2:])
    assert not any("shoulder" in f or "inertia" in f for f in failures)


def test_check_urdf_takes_package_for_a_xacro_that_finds_one(tmp_path):
    # The xacro includes a file of a package that only --package says where to find.
    write(
        tmp_path / "pkgs" / "pendulum_description" / "urdf" / "arm.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        + URDF[URDF.index('<link name="arm">') : URDF.index("</robot>")]
        + "</robot>",
    )
    write(
        tmp_path / "p.urdf.xacro",
        '<robot name="pendulum" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/>'
        '<xacro:include filename="$(find pendulum_description)/urdf/arm.xacro"/></robot>',
    )
    write(tmp_path / "p.xml", MJCF)
    argv = ["check", "--urdf", "p.urdf.xacro", "--mjcf", "p.xml"]
    missing = run_cli(*argv, cwd=tmp_path, env={"ROS_PACKAGE_PATH": "", "AMENT_PREFIX_PATH": ""})
    assert missing.code == 4 and "pendulum_description" in missing.stderr
    assert "pass --package pendulum_description=<folder>" in missing.stderr  # no robot.yaml
    assert "robot.yaml" not in missing.stderr
    result = run_cli(
        *argv, "--package", "pendulum_description=pkgs/pendulum_description", cwd=tmp_path
    )
    assert result.code == EXIT_OK, result.stdout + result.stderr
    assert "checks pass, but 1 actuation problem" in result.stdout


def test_check_urdf_takes_xacro_arguments_as_convert_and_the_xacro_command_do(tmp_path):
    """A xacro whose include needs an argument (as ur_description's ur_type): the error's
    advice, NAME:=VALUE after the other arguments, is taken (it was refused as a manifest),
    and so is --xacro-arg; a misspelt argument is refused at the command line."""
    write(
        tmp_path / "urdf" / "arm.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        + URDF[URDF.index('<link name="arm">') : URDF.index("</robot>")]
        + "</robot>",
    )
    write(
        tmp_path / "p.urdf.xacro",
        '<robot name="pendulum" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="part" default="missing"/>\n  <link name="base"/>\n'
        '  <xacro:include filename="urdf/$(arg part).xacro"/>\n</robot>\n',
    )
    write(tmp_path / "p.xml", MJCF)
    argv = ["check", "--urdf", "p.urdf.xacro", "--mjcf", "p.xml"]
    defaults = run_cli(*argv, cwd=tmp_path)
    assert defaults.code == 4 and "urdf/missing.xacro" in defaults.stderr
    for given in (["part:=arm"], ["--xacro-arg", "part:=arm"]):
        result = run_cli(*argv, *given, cwd=tmp_path)
        assert result.code == EXIT_OK, result.stdout + result.stderr
    misspelt = run_cli(*argv, "part:=arm", "prat:=arm", cwd=tmp_path)
    assert misspelt.code == 2 and "did you mean 'part'?" in misspelt.stderr
    assert "manifest" not in misspelt.stderr
    urdf = run_cli("check", "--urdf", "p.xml", "--mjcf", "p.xml", "part:=arm", cwd=tmp_path)
    assert urdf.code == 2 and "not a xacro file" in urdf.stderr
    alone = run_cli("check", "part:=arm", cwd=tmp_path)
    assert alone.code == 2 and "go with --urdf" in alone.stderr


def test_check_urdf_points_a_xacro_mistake_at_the_included_file_and_line(tmp_path):
    write(
        tmp_path / "urdf" / "arm.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="arm"/>\n'
        '  <joint name="swing" type="revolute"><parent link="bsae"/><child link="arm"/>\n'
        '    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
        "</robot>\n",
    )
    write(
        tmp_path / "urdf" / "p.urdf.xacro",
        '<robot name="pendulum" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="base"/>\n  <xacro:include filename="arm.xacro"/>\n</robot>\n',
    )
    write(tmp_path / "p.xml", MJCF)
    result = run_cli("check", "--urdf", "urdf/p.urdf.xacro", "--mjcf", "p.xml", cwd=tmp_path)
    assert result.code == 4, result.stderr
    assert "error: urdf/arm.xacro:3:" in result.stderr and "'bsae'" in result.stderr
    assert "of its expansion]" in result.stderr


def test_the_console_names_each_check_and_never_says_passed_over_a_robot_that_cannot_stand(
    tmp_path,
):
    """A two-wheeled balancer cannot stand without a controller: the console says so with the
    reason, as the report does, instead of "check passed"."""
    from tests.control import robots

    write(tmp_path / "robot.urdf", robots.balancer())
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\n",
    )
    assert run_cli("build", str(tmp_path / "robot.yaml")).code == EXIT_OK
    result = run_cli("check", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_OK, result.stderr
    lines = result.stdout.splitlines()
    assert "mjcfbuild: check passed" not in lines
    assert (
        lines[-2].startswith(
            "mjcfbuild: checks pass, but the robot cannot stand without a controller ("
        )
        and "a line" in lines[-2]
        and lines[-2].endswith("the stand test was not run")
    )
    stand = next(line for line in lines if line.strip().startswith("stand 5 s"))
    assert "NOT RUN: needs a controller" in stand
    for name in ("loads", "hold home 1 s", "1 s pseudorandom control", "every moving joint"):
        assert any(line.strip().startswith(name) for line in lines), name


def test_the_console_of_a_robot_that_stands_says_passed_with_each_result(tmp_path):
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", str(arm / "robot.yaml")).code == EXIT_OK
    result = run_cli("check", str(arm / "robot.yaml"))
    assert result.code == EXIT_OK, result.stderr
    lines = result.stdout.splitlines()
    assert "mjcfbuild: check passed" in lines
    hold = next(line for line in lines if line.strip().startswith("hold home 1 s"))
    assert "largest deviation" in hold
    assert any(line.strip().startswith("joint speeds") for line in lines)
    # An input edited since the build: the check is of the model as built, and says so.
    xacro = arm / "urdf" / "arm.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('<mass value="2.0"/>', '<mass value="2.5"/>', 1))
    result = run_cli("check", str(arm / "robot.yaml"))
    assert result.code == EXIT_OK, result.stderr
    assert result.stdout.splitlines()[-2] == (
        "mjcfbuild: check passed, of the model as it was built: it is out of date (expand "
        "urdf/arm.urdf.xacro: input changed: urdf/arm.urdf.xacro); `mjcfbuild build "
        f"{arm / 'robot.yaml'}` makes it current"
    )


def test_a_check_that_fails_says_so_on_its_own_line(tmp_path):
    arm = copy_example("arm", tmp_path)
    manifest = arm / "robot.yaml"
    manifest.write_text(
        manifest.read_text().replace(
            '- {joints: ["*finger*"], frequency: 5}',
            '- {joints: ["*finger*"], frequency: 5}\n    - {joints: ["*"], forcerange: [-0.05, 0.05]}',
        )
    )
    assert run_cli("build", str(manifest)).code == EXIT_CHECK
    result = run_cli("check", str(manifest))
    assert result.code == EXIT_CHECK
    table = [line for line in result.stdout.splitlines() if line.startswith("  ")]
    lines = {line[:31].strip(): line[31:] for line in table}
    assert lines["hold home 1 s"].startswith("FAILED: largest deviation ")
    assert lines["loads"] == "yes" and not lines["joints"].startswith("FAILED")
    assert "mjcfbuild: 1 check(s) failed" in result.stdout.splitlines()
    quiet = run_cli("check", str(manifest), "-q")
    assert quiet.code == EXIT_CHECK and quiet.stdout == ""
    assert quiet.stderr.startswith("mjcfbuild: check failed: holding home's ctrl for 1 s")
    quietly_failed = run_cli("build", str(manifest), "-q")
    assert quietly_failed.code == EXIT_CHECK and quietly_failed.stdout == ""
    assert quietly_failed.stderr.count("\n") == 1


def test_check_writes_the_same_check_json_as_the_build_mjcf_parts_included(tmp_path):
    """One code path: `mjcfbuild check` runs the build's check (steps.check.check_built), so the
    MJCF part's comparison the build wrote is not lost, and check.json and the report come out
    byte for byte as the build wrote them."""
    example = copy_example("arm_mjcf_gripper", tmp_path)
    assert run_cli("build", str(example / "robot.yaml")).code == EXIT_OK
    record = example / "mjcf/.mjcfbuild/check.json"
    report = example / "mjcf/report/report.md"
    built, built_report = record.read_bytes(), report.read_bytes()
    parts = CheckResults.from_json(built).parts
    assert parts and all(part.configurations > 0 for part in parts.values()), parts
    record.unlink()
    result = run_cli("check", str(example / "robot.yaml"))
    assert result.code == EXIT_OK, result.stderr
    assert record.read_bytes() == built
    assert report.read_bytes() == built_report
    prefix = next(iter(parts))
    assert any(
        line.strip().startswith(f"MJCF part {prefix}") for line in result.stdout.splitlines()
    )


def test_a_urdf_and_mjcf_pair_is_held_to_mujoco_ros2_controls_rules(tmp_path):
    """`check --urdf --mjcf` (a model from any tool, the reference converter's) adds the
    runtime section a build's check has: a model without the MJCF sensors the <ros2_control>
    block reads fails there, naming them (it said nothing of them)."""
    from tests.conftest import two_link_urdf

    block = (
        '<ros2_control name="s" type="system"><hardware><plugin>mujoco_ros2_control/'
        'MujocoSystemInterface</plugin><param name="initial_keyframe">home</param></hardware>'
        '<joint name="hinge"><command_interface name="position"/>'
        '<state_interface name="position"/></joint><sensor name="imu">'
        '<param name="mujoco_type">imu</param><param name="frame_name">arm</param></sensor>'
        "</ros2_control>"
    )
    urdf = write(tmp_path / "robot.urdf", two_link_urdf(extra=block))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    assert run_cli("build", "-q", str(tmp_path / "robot.yaml")).code == EXIT_OK
    model = tmp_path / "mjcf" / "r.xml"
    result = run_cli("check", "--urdf", str(urdf), "--mjcf", str(model))
    assert result.code == EXIT_OK, result.stdout + result.stderr
    assert "mujoco_ros2_control          1 joint, 1 sensor" in result.stdout
    text = model.read_text()
    start, end = text.index("<sensor>"), text.index("</sensor>") + len("</sensor>")
    bare = write(tmp_path / "mjcf" / "bare.xml", text[:start] + text[end:])
    result = run_cli("check", "--urdf", str(urdf), "--mjcf", str(bare))
    assert result.code == EXIT_CHECK
    assert "reads the MJCF framequat 'imu_quat', which the model does not have" in result.stderr


def test_the_pair_checks_runtime_failures_name_the_xacro_files_lines(tmp_path):
    """Its lines were the expanded text's (line 245 of a 172-line xacro file)."""
    from tests.conftest import two_link_urdf

    urdf = two_link_urdf(
        extra='<link name="tool"/><joint name="mount" type="fixed"><parent link="arm"/>'
        '<child link="tool"/></joint>\n'
        '<ros2_control name="s" type="system"><hardware><plugin>mujoco_ros2_control/'
        "MujocoSystemInterface</plugin></hardware>\n"
        '<joint name="mount"><state_interface name="position"/></joint></ros2_control>'
    )
    xacro = urdf.replace(
        '<robot name="two_link">',
        '<robot name="two_link" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:property name="unused" value="1"/>\n<xacro:property name="other" value="2"/>',
    )
    source = write(tmp_path / "robot.urdf.xacro", xacro)
    write(
        tmp_path / "robot.urdf",
        urdf.replace("<ros2_control", "<!-- --><no_block").replace(
            "</ros2_control>", "</no_block>"
        ),
    )
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    assert run_cli("build", "-q", "--no-check", str(tmp_path / "robot.yaml")).code == EXIT_OK
    result = run_cli("check", "--urdf", str(source), "--mjcf", str(tmp_path / "mjcf" / "r.xml"))
    line = next(n for n, text in enumerate(xacro.splitlines(), 1) if '<joint name="mount">' in text)
    assert (
        f"robot.urdf.xacro:{line}: <ros2_control> joint 'mount' is a fixed joint" in result.stderr
    )
