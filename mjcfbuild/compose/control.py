"""How MJCF parts' joints join the home pose and the actuator rules.

A part's hinge and slide joints are added to the robot as URDF joints (prefixed) so that
robot.yaml ``home`` patterns and ``actuators.rules`` can name them and ranges are checked.
A part drives its joints with its own actuators: mjcfbuild generates an actuator only for a
part joint a rule names and no actuator of the part drives; the others are passive (a
hand-tuned gripper's linkage follows its driven joints through equalities or tendons).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from mjcfbuild.compose.attach import AttachedPart
from mjcfbuild.compose.mjcf import part_joints_as_urdf
from mjcfbuild.control.choose import matches
from mjcfbuild.manifest.simulation import ActuatorSettings
from mjcfbuild.urdf.model import Robot


@dataclass
class PartControl:
    """The robot as home and the actuator choice see it, with the parts' own home."""

    home_robot: Robot  # every hinge and slide joint of the parts added
    actuator_robot: Robot  # only the part joints a rule names
    fallback: dict[str, float] = field(default_factory=dict)  # joint -> the part's home
    preset_qpos: dict[str, list[float]] = field(default_factory=dict)  # ball joints
    preset_ctrl: dict[str, float] = field(default_factory=dict)  # actuator -> home ctrl
    undriven: list[str] = field(default_factory=list)  # part joints no part actuator drives


def with_parts(robot: Robot, parts: list[AttachedPart], settings: ActuatorSettings) -> PartControl:
    """``robot`` with the joints of ``parts``, and the parts' home."""
    joints = [j for part in parts for j in part_joints_as_urdf(part.summary, part.prefix)]
    patterns = [pattern for rule in settings.rules for pattern in rule.joints]
    ruled = [joint for joint in joints if matches(joint.name, patterns)]
    control = PartControl(
        home_robot=replace(robot, joints=[*robot.joints, *joints]),
        actuator_robot=replace(robot, joints=[*robot.joints, *ruled]),
    )
    for part in parts:
        for joint in part.summary.joints:
            name = part.prefix + joint.name
            values = part.summary.home_qpos.get(joint.name, [])
            if len(values) == 1:
                control.fallback[name] = values[0]
            elif values:
                control.preset_qpos[name] = values
            if not joint.actuated and joint.type != "free":
                control.undriven.append(name)
        for actuator, value in part.summary.home_ctrl.items():
            control.preset_ctrl[part.prefix + actuator] = value
    return control
