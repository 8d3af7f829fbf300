"""Bad actuator and home settings: one line naming the robot.yaml line and the choices, exit 3,
nothing written."""

from __future__ import annotations

import pytest

from tests.conftest import run_cli, two_link_urdf, write

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
        "'knee' matches no moving joint (moving joints: hinge)",
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
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + extra)
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == 3, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr
    assert where in lines[0] and message in lines[0], lines[0]
    assert not (tmp_path / "mjcf" / "r.xml").exists()
