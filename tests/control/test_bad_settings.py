"""Bad actuator and home settings: one line naming the robot.yaml line and the choices, exit 3,
nothing written."""

from __future__ import annotations

import pytest

from tests.conftest import INERTIA, run_cli, two_link_urdf, write

# A tool on a fixed joint and a finger mimicking the hinge, beside the two links.
TOOL_AND_FINGER = f"""
  <link name="tool">{INERTIA}</link>
  <joint name="tool_joint" type="fixed"><parent link="arm"/><child link="tool"/></joint>
  <link name="finger">{INERTIA}</link>
  <joint name="finger_joint" type="prismatic"><parent link="arm"/><child link="finger"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.1" effort="10" velocity="1"/>
    <mimic joint="hinge" multiplier="0.05"/></joint>
"""

CASES = {
    "a rule that matches no joint": (
        "actuators:\n  rules:\n    - {joints: [elbow*], kp: 5}\n",
        "robot.yaml:5",
        "rule matches no actuated joint (elbow*) (actuated joints: hinge)",
    ),
    "a rule whose word is misspelt": (
        "actuators:\n  rules:\n    - {joints: ['*hnge*'], kp: 5}\n",
        "robot.yaml:5",
        "rule matches no actuated joint (*hnge*); did you mean 'hinge'?",
    ),
    "a gain that is not positive": (
        "actuators:\n  rules:\n    - {joints: [hinge], kp: -5}\n",
        "robot.yaml:5",
        "greater than 0",
    ),
    "a home value outside the range": (
        "home:\n  hinge: 2.5\n",
        "robot.yaml:4",
        "2.5 is outside the range of joint 'hinge' [-1.5, 1.5]",
    ),
    "an unknown joint in home": (
        "home:\n  knee: 0.2\n",
        "robot.yaml:4",
        "'knee' matches no moving joint (moving joints: hinge, finger_joint)",
    ),
    "a rule naming a mimic follower": (
        "actuators:\n  rules:\n    - {joints: [finger_joint], kp: 5}\n",
        "robot.yaml:5",
        "rule matches no actuated joint: 'finger_joint' is a mimic follower: its leader 'hinge' "
        "drives it through a joint equality, and it has no actuator of its own (name its leader "
        "'hinge' instead: its actuator moves both)",
    ),
    "a rule naming a fixed joint": (
        "actuators:\n  rules:\n    - {joints: [tool_joint], kp: 5}\n",
        "robot.yaml:5",
        "rule matches no actuated joint: 'tool_joint' is a fixed joint, which nothing moves "
        "(remove it from the rule; actuated joints: hinge)",
    ),
    "a home value for a fixed joint": (
        "home:\n  tool_joint: 0.1\n",
        "robot.yaml:4",
        "home.tool_joint: 'tool_joint' is a fixed joint, which has no position to set "
        "(remove it; moving joints: hinge, finger_joint)",
    ),
    "the removed ros2_control section": (
        "ros2_control: {actuators: true}\n",
        "robot.yaml:3",
        "the ros2_control section is gone",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_setting(tmp_path, case):
    extra, where, message = CASES[case]
    write(tmp_path / "robot.urdf", two_link_urdf(TOOL_AND_FINGER))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + extra)
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == 3, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr
    assert where in lines[0] and message in lines[0], lines[0]
    assert not (tmp_path / "mjcf" / "r.xml").exists()
