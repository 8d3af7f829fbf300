"""Which actuator drives each moving joint, and where that decision came from.

Sources, strongest first: an actuator the user wrote (raw MJCF, inputs file, URDF
``<mujoco_inputs>``) - then an ``actuators.rules`` entry that names a type - then the joint's
``<ros2_control>`` command interface - then ``actuators.default``, for joints a ROS 1
``<transmission>`` names (source ``transmission``) and all others (source ``default``). Gains
and joint dynamics come from the first matching rule, else the defaults. Mimic followers are
driven through their equality, never by an actuator.
"""

from __future__ import annotations

import fnmatch
from dataclasses import asdict, dataclass

from mjcfbuild.errors import ManifestError
from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.manifest.simulation import ActuatorRule, ActuatorSettings
from mjcfbuild.urdf.model import Joint, Robot

# ros2_control command interfaces (and transmission hardware interfaces) as MuJoCo actuators.
_BY_COMMAND = {"position": "position", "velocity": "velocity", "effort": "motor"}
# A joint with several command interfaces gets one actuator, of the first kind listed here.
_COMMAND_PREFERENCE = ("position", "velocity", "effort")


@dataclass(frozen=True)
class ActuatorChoice:
    """The actuator of one joint, before its gains are worked out from the compiled model."""

    joint: str
    type: str  # position, velocity, motor, none, or user (written by the user)
    source: str  # rule, ros2_control, transmission, default, user
    kp: float | None = None
    kv: float | None = None
    frequency: float = 10.0
    damping_ratio: float = 1.0
    forcerange: tuple[float, float] | None = None
    effort_limited: bool = False  # forcerange is the URDF's effort (no rule gave one)
    armature: float | None = None
    damping: float | None = None
    frictionloss: float | None = None
    gravcomp: bool = False
    rule: int | None = None  # index of the matching actuators.rules entry
    stiffen: bool = True  # default gains: stiffened where gravity at home would bend the joint
    motor: dict | None = None  # issue 33: the rule's drive at the output (control.motors.Drive)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)


def matches(name: str, patterns: list[str]) -> bool:
    """Whether ``name`` matches one of the ``*``/``?`` patterns (the collision rules' language)."""
    return any(fnmatch.fnmatchcase(name, pattern) for pattern in patterns)


def actuated_joints(robot: Robot) -> list[Joint]:
    """The joints an actuator may drive: moving, and not following another through <mimic>."""
    return [joint for joint in robot.joints if joint.moves and joint.mimic is None]


def choose_actuators(
    robot: Robot,
    control: Ros2Control,
    settings: ActuatorSettings,
    user_driven: set[str],
) -> list[ActuatorChoice]:
    """One choice per actuated joint, in URDF order (``none`` choices included)."""
    commands = {joint.name: joint.commands for joint in control.joints if joint.commands}
    transmitted = {t.joint for t in control.transmissions}
    choices = []
    for joint in actuated_joints(robot):
        index, rule = _first_rule(joint.name, settings.rules)
        if joint.name in user_driven:
            kind, source = "user", "user"
        elif rule is not None and rule.type is not None:
            kind, source = rule.type, "rule"
        elif joint.name in commands:
            preferred = min(commands[joint.name], key=_preference)
            kind, source = _BY_COMMAND.get(preferred, settings.default), "ros2_control"
        elif joint.name in transmitted:
            # A ROS 1 transmission names an actuated joint; its hardware interface is what a
            # ROS controller commands (an effort interface usually under a position PID), not
            # how the joint should be driven without one, so the default type applies.
            kind, source = _default_type(joint, settings), "transmission"
        else:
            kind, source = _default_type(joint, settings), "default"
        choices.append(_choice(joint, kind, source, settings, index, rule))
    return choices


def _choice(
    joint: Joint,
    kind: str,
    source: str,
    settings: ActuatorSettings,
    index: int | None,
    rule: ActuatorRule | None,
) -> ActuatorChoice:
    """The choice for ``joint``: gains and dynamics from its rule, else the defaults."""
    if rule is None:
        return ActuatorChoice(
            joint.name,
            kind,
            source,
            frequency=settings.frequency,
            damping_ratio=settings.damping_ratio,
            forcerange=_effort_range(joint),
            effort_limited=_effort_range(joint) is not None,
        )
    return ActuatorChoice(
        joint.name,
        kind,
        source,
        kp=rule.kp,
        kv=rule.kv,
        frequency=rule.frequency or settings.frequency,
        damping_ratio=rule.damping_ratio or settings.damping_ratio,
        forcerange=rule.forcerange or _effort_range(joint),
        effort_limited=rule.forcerange is None and _effort_range(joint) is not None,
        armature=rule.armature,
        damping=rule.damping,
        frictionloss=rule.frictionloss,
        gravcomp=bool(rule.gravcomp),
        rule=index,
        stiffen=rule.kp is None and rule.frequency is None,
    )


def check_rules(robot: Robot, settings: ActuatorSettings, manifest_label: str) -> None:
    """Refuse an actuator rule whose patterns match no actuated joint (always a typo)."""
    names = [joint.name for joint in actuated_joints(robot)]
    for index, rule in enumerate(settings.rules):
        if not any(matches(name, rule.joints) for name in names):
            raise ManifestError(
                f"rule matches no actuated joint ({', '.join(rule.joints)})",
                file=f"{manifest_label} actuators.rules[{index}].joints",
                hint=f"actuated joints: {listing(names)}",
            )


def _first_rule(name: str, rules: list[ActuatorRule]) -> tuple[int | None, ActuatorRule | None]:
    for index, rule in enumerate(rules):
        if matches(name, rule.joints):
            return index, rule
    return None, None


def _preference(command: str) -> int:
    return _COMMAND_PREFERENCE.index(command) if command in _COMMAND_PREFERENCE else 99


def _default_type(joint: Joint, settings: ActuatorSettings) -> str:
    # A continuous joint is a wheel or a spinner: position control of an unbounded angle
    # winds up, so it gets a velocity servo, as ros2_control's wheel controllers use.
    if settings.default == "position" and joint.kind == "continuous":
        return "velocity"
    return settings.default


def _effort_range(joint: Joint) -> tuple[float, float] | None:
    effort = joint.limit.effort if joint.limit is not None else None
    return (-effort, effort) if effort else None


def listing(names: list[str], most: int = 12) -> str:
    """Names for an error message's hint, the first ``most`` of them."""
    shown = ", ".join(names[:most])
    return (
        shown + (f", ... ({len(names)} in all)" if len(names) > most else "") if names else "none"
    )
