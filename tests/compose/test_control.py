"""MJCF parts' joints in the home pose and the actuator rules (no build: the choice itself)."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.compose.attach import AttachedPart
from mjcfbuild.compose.control import with_parts
from mjcfbuild.compose.mjcf import PartJoint, PartSummary
from mjcfbuild.control.choose import choose_actuators
from mjcfbuild.control.home import home_values
from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.manifest.simulation import ActuatorSettings
from mjcfbuild.urdf.model import Joint, Limit, Link, Robot

ARM = Robot(
    "arm",
    [Link("base"), Link("tool")],
    [Joint("wrist", "revolute", "base", "tool", limit=Limit(-1.0, 1.0, 1.0, 1.0))],
)


def hand() -> AttachedPart:
    joints = [
        PartJoint("driven", "hinge", "finger", (0.0, 1.0), actuated=True),
        PartJoint("loose", "slide", "pad", (0.0, 0.02), actuated=False),
        PartJoint("wrist", "ball", "knuckle", None, actuated=False),
    ]
    summary = PartSummary(
        label="hand.xml",
        bodies=["finger", "pad", "knuckle"],
        sites=[],
        joints=joints,
        actuators=["grip"],
        names={},
        home_qpos={"driven": [0.4], "loose": [0.01], "wrist": [0.0, 1.0, 0.0, 0.0]},
        home_ctrl={"grip": 0.4},
        home_source="keyframe 'home'",
    )
    return AttachedPart(
        "robot.yaml attach[0]", "h_", "tool", (0, 0, 0), (1, 0, 0, 0), Path(), summary
    )


def test_only_part_joints_a_rule_names_reach_the_actuator_choice():
    settings = ActuatorSettings(rules=[{"joints": ["h_*"], "damping": 1.0}])
    control = with_parts(ARM, [hand()], settings)
    assert [j.name for j in control.actuator_robot.joints] == ["wrist", "h_driven", "h_loose"]
    # The joint the part drives stays the part's ('user'); the undriven one a rule names gets one.
    choices = choose_actuators(control.actuator_robot, Ros2Control(), settings, {"h_driven"})
    kinds = {choice.joint: choice.type for choice in choices}
    assert kinds == {"wrist": "position", "h_driven": "user", "h_loose": "position"}
    without_rule = with_parts(ARM, [hand()], ActuatorSettings())
    assert [j.name for j in without_rule.actuator_robot.joints] == ["wrist"]
    assert without_rule.undriven == ["h_loose", "h_wrist"]


def test_home_takes_the_part_home_unless_robot_yaml_names_the_joint():
    control = with_parts(ARM, [hand()], ActuatorSettings())
    values = home_values(
        control.home_robot, Ros2Control(), {"h_loose": 0.015}, fallback=control.fallback
    )
    found = {value.joint: (value.value, value.source) for value in values}
    assert found["h_driven"] == (0.4, "part")
    assert found["h_loose"] == (0.015, "robot.yaml")
    assert control.preset_qpos == {"h_wrist": [0.0, 1.0, 0.0, 0.0]}
    assert control.preset_ctrl == {"h_grip": 0.4}
