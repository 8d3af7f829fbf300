"""The Menagerie test's speed bound: each joint's top speed against its URDF velocity limit,
the fastest joint in check.json, and a failure that names the joint and its limit."""

from __future__ import annotations

import json

import pytest

from mjcfbuild.check.results import FastestJoint
from mjcfbuild.check.speeds import DRIVEN_MULTIPLE, FREE_MULTIPLE, joint_speeds, speed_results
from mjcfbuild.control.motors import URDF_LIMITS
from tests.conftest import run_cli, write
from tests.control.test_home import _urdf

DRIVE = {"joint": "knee", "motor": {"motor": "go1_knee", "no_load_speed": 20.0}}


def test_a_driven_joint_is_held_to_its_limit_and_a_free_one_to_a_multiple():
    speeds = joint_speeds(
        {"knee": 1.4 * 20.0, "elbow": 10 * 2.0, "wrist": 60 * 2.0},
        {"knee": 20.0, "elbow": 2.0, "wrist": 2.0},
        {"knee": "hinge", "elbow": "hinge", "wrist": "hinge"},
        [DRIVE],
    )
    bound, failures = speed_results(speeds)
    assert bound.fastest == FastestJoint("wrist", 120.0, 2.0)
    assert [s.joint for s in bound.over_limit] == ["elbow", "knee", "wrist"]
    assert len(failures) == 1 and failures[0].startswith(
        f"joint 'wrist' reached 120 rad/s under pseudorandom control, more than {FREE_MULTIPLE:g} "
        "times its velocity limit 2 rad/s (urdf)"
    )
    _, failures = speed_results(joint_speeds({"knee": 1.6 * 20.0}, {"knee": 20.0}, {}, [DRIVE]))
    assert len(failures) == 1 and f"more than {DRIVEN_MULTIPLE:g} times" in failures[0]


@pytest.mark.parametrize("placeholder", [None, 0.0, -1.0, 1e9, 1e16])
def test_a_joint_without_a_limit_takes_its_motors_no_load_speed_else_the_default(placeholder):
    (driven,) = joint_speeds({"knee": 1.0}, {"knee": placeholder}, {}, [DRIVE])
    assert (driven.limit, driven.limit_from) == (20.0, "motor")
    (slide,) = joint_speeds({"rail": 1.0}, {"rail": placeholder}, {"rail": "slide"}, [])
    assert (slide.limit, slide.limit_from, slide.unit) == (10.0, "default", "m/s")


def test_a_placeholder_speed_in_a_line_drawn_from_the_urdf_is_no_limit_either():
    # prius's steering joint: velocity="1000000", so its URDF line's no-load speed is 1e6 too.
    line = {"joint": "steer", "motor": {"motor": URDF_LIMITS, "no_load_speed": 1e6}}
    (steer,) = joint_speeds({"steer": 62.0}, {"steer": 1e6}, {}, [line])
    assert (steer.limit, steer.limit_from) == (100.0, "default")


def test_a_runaway_joint_fails_the_build_naming_it_and_its_limit(tmp_path):
    # A floating base with a massless root (repaired to a tiny mass): a servo without the URDF's
    # speed line spins the root around at hundreds of rad/s, where its URDF says 1 rad/s.
    write(tmp_path / "robot.urdf", _urdf(massless_root=True))
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\n"
        "actuators: {speed_limits: false}\n",
    )
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == 6, result.stderr
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    # It also fails to stand (a 1 kg arm on a 10 g base); the speed has its own failure.
    speed = [f for f in check["failures"] if "joint 'hinge' reached" in f]
    assert speed and "times its velocity limit 1 rad/s (urdf)" in speed[0]
    fastest = check["max_joint_speed"]
    assert fastest["joint"] == "hinge" and fastest["limit"] == 1 and fastest["speed"] > 20


def test_the_quadruped_with_motors_stays_within_its_drives(tmp_path):
    from tests.control.test_motors import _build

    _build(tmp_path)
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"], check["failures"]
    fastest = check["max_joint_speed"]
    assert set(fastest) == {"joint", "speed", "limit"}
    assert fastest["speed"] <= DRIVEN_MULTIPLE * fastest["limit"]


def test_the_urdf_speed_line_keeps_the_same_joint_near_its_limit(tmp_path):
    # The same robot with default settings: the servo is a <dcmotor> whose torque falls to zero
    # at the URDF's 1 rad/s, with the rotor inertia that keeps the line stable.
    write(tmp_path / "robot.urdf", _urdf(massless_root=True))
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\n",
    )
    run_cli("build", str(tmp_path / "robot.yaml"))
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert not [f for f in check["failures"] if "joint 'hinge' reached" in f]
    fastest = check["max_joint_speed"]
    assert fastest["joint"] == "hinge" and fastest["speed"] < DRIVEN_MULTIPLE * fastest["limit"]
    model = (tmp_path / "mjcf/r.xml").read_text()
    assert '<dcmotor name="hinge" joint="hinge" input="pos"' in model


# An elbow whose range leaves out zero (jaco's, from differentiable-robot-model): the test
# starts at qpos0, 2 rad outside the range, and the limit throws the light arm back at 70
# times its 0.2 rad/s, which no servo setting can help.
_OUTSIDE_AT_ZERO = """<robot name="r">
  <link name="root"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="arm"><inertial><origin xyz="0 0 0.1"/><mass value="0.05"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.02" length="0.2"/></geometry></collision></link>
  <joint name="elbow" type="revolute"><parent link="root"/><child link="arm"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 1 0"/>
    <limit lower="2" upper="2.5" effort="5" velocity="0.2"/></joint>
</robot>"""


def test_speeds_thrown_by_a_limit_at_qpos0_are_measured_again_inside_the_ranges(tmp_path):
    import mujoco

    from mjcfbuild.check.control import menagerie_test, outside_at_qpos0

    write(tmp_path / "robot.urdf", _OUTSIDE_AT_ZERO)
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == 0, result.stderr
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"], check["failures"]
    assert check["speed_bound"]["measured_from"] == (
        "qpos0 clipped into the joint ranges (elbow outside at qpos0)"
    )
    assert check["max_joint_speed"]["speed"] < DRIVEN_MULTIPLE * 0.2
    # From qpos0 itself the same model fails the bound: the limit's throw, not the servo.
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf/scene.xml"))
    assert menagerie_test(model).top_speeds["elbow"] > FREE_MULTIPLE * 0.2
    outside, clipped = outside_at_qpos0(model)
    assert outside == ["elbow"] and clipped == [2.0]


def test_speeds_within_the_bound_keep_the_measurement_from_qpos0(tmp_path):
    # Outside its range at qpos0 too, but thrown back within the bound: measured once, as
    # before (panda's and go1's reports stay the same).
    write(tmp_path / "robot.urdf", _urdf(lower=1.0, upper=1.4))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    assert run_cli("build", str(tmp_path / "robot.yaml")).code == 0
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert "measured_from" not in check["speed_bound"]
    assert 1.0 < check["max_joint_speed"]["speed"] < FREE_MULTIPLE * 1.0  # the limit's throw


def test_a_joint_without_an_effort_is_told_its_servo_has_no_line():
    (speed,) = joint_speeds(
        {"lift": 6.0}, {"lift": 0.05}, {"lift": "slide"}, [{"joint": "lift", "type": "position"}]
    )
    _, failures = speed_results([speed])
    assert len(failures) == 1
    assert "no force limit (the URDF gives no effort)" in failures[0]
    assert "forcerange" in failures[0]


def test_a_users_servo_is_not_said_to_lack_the_effort_its_urdf_gives():
    """The reference demo's own position servos (its inputs file) are held by their joints'
    actuatorfrcrange from the URDF's effort of 1000: "the URDF gives no effort" was false."""
    record = {"joint": "joint1", "type": "position", "source": "user"}
    (speed,) = joint_speeds({"joint1": 2e4}, {"joint1": 3.14}, {}, [record])
    _, failures = speed_results([speed])
    assert len(failures) == 1 and "gives no effort" not in failures[0], failures
