"""Which actuator drives each moving joint, and where that decision came from.

Sources, strongest first: an actuator the user wrote (raw MJCF, inputs file, URDF
``<mujoco_inputs>``) - then an ``actuators.rules`` entry that names a type - then the joint's
``<ros2_control>`` command interface - then ``actuators.default``, for joints a ROS 1
``<transmission>`` commands (source ``transmission``) and all others (source ``default``; a
transmission that only reads a joint, ``JointStateInterface``, commands nothing). Gains
and joint dynamics come from the first matching rule, else the defaults. Mimic followers are
driven through their equality, never by an actuator; free (URDF ``floating``) and planar
joints never get a generated actuator: one servo cannot drive several degrees of freedom.

A continuous joint is not taken for a wheel by its type alone (arms and legs have continuous
joints too): it is a *wheel candidate*, given a position servo here, which
:mod:`mjcfbuild.control.wheels` turns into a velocity servo where the compiled model shows a
wheel (see there).

URDF effort and velocity limits that are not positive (``effort="-1"``, ``velocity="0"``) are
the "unknown" marker of many descriptions: they are treated as no limit, and reported.
"""

from __future__ import annotations

import fnmatch
from dataclasses import replace
from typing import TYPE_CHECKING

from mjcfbuild.actuators import ActuatorChoice, resolve_choice
from mjcfbuild.errors import ManifestError
from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.sources.packages import listing, suggestion
from mjcfbuild.urdf.model import Joint, Robot

if TYPE_CHECKING:  # pydantic's models: a worker that only reads settings from a payload skips them
    from mjcfbuild.manifest.simulation import ActuatorRule, ActuatorSettings

# ros2_control command interfaces (and transmission hardware interfaces) as MuJoCo actuators.
# torque and force are effort to mujoco_ros2_control.
_BY_COMMAND = {
    "position": "position",
    "velocity": "velocity",
    "effort": "motor",
    "torque": "motor",
    "force": "motor",
}
# A joint with several command interfaces gets one actuator, of the first kind listed here
# (the runtime's own order): the runtime commands that interface directly.
_COMMAND_PREFERENCE = ("position", "velocity", "effort", "torque", "force")


def matches(name: str, patterns: list[str]) -> bool:
    """Whether ``name`` matches one of the ``*``/``?`` patterns (the collision rules' language)."""
    return any(fnmatch.fnmatchcase(name, pattern) for pattern in patterns)


# Joints with several degrees of freedom: no single generated servo can drive them.
MULTI_DOF_KINDS = ("floating", "planar")


def actuated_joints(robot: Robot) -> list[Joint]:
    """The joints an actuator may drive: moving with one degree of freedom, and not following
    another through <mimic>."""
    return [
        joint
        for joint in robot.joints
        if joint.moves and joint.mimic is None and joint.kind not in MULTI_DOF_KINDS
    ]


# A joint range wider than this (rad or m) is a placeholder for "unlimited" (+-1e16 is common).
PLACEHOLDER_RANGE = 1e4


def placeholder_range(bounds: tuple[float, float]) -> bool:
    """Whether a joint range is a stand-in for no range at all."""
    return max(abs(bounds[0]), abs(bounds[1])) > PLACEHOLDER_RANGE


def limit_notes(robot: Robot) -> list[str]:
    """A warning per actuated joint whose URDF effort or velocity limit is not positive, or
    whose range is a placeholder."""
    from mjcfbuild.urdf.limits import joint_range

    notes = []
    for joint in actuated_joints(robot):
        limit = joint.limit
        if limit is None:
            continue
        # Started with the URDF's file and line, which the console places in a xacro source.
        where = f"{robot.source}:{joint.line}: " if joint.line else ""
        bounds = joint_range(joint)
        if bounds is not None and placeholder_range(bounds):
            notes.append(
                f"{where}joint '{joint.name}' has the range [{bounds[0]:g}, {bounds[1]:g}]: "
                "taken for no range, its servo gets no ctrlrange; give the real limits, or "
                'type="continuous" for a joint without stops'
            )
        # What gives each limit in robot.yaml: a rule's forcerange bounds the force, only a
        # drive (a rule's motor) gives a speed.
        for name, value, other in (
            ("effort", limit.effort, "a rule's forcerange"),
            ("velocity", limit.velocity, "a rule's motor (its no_load_speed)"),
        ):
            if value is not None and value <= 0:
                notes.append(
                    f"{where}joint '{joint.name}' has {name}=\"{value:g}\": not a limit, "
                    f"taken as unknown (no {name} limit); give the real one in the URDF or "
                    f"with {other}"
                )
    return notes


def choose_actuators(
    robot: Robot,
    control: Ros2Control,
    settings: ActuatorSettings,
    user_driven: set[str],
) -> list[ActuatorChoice]:
    """One choice per actuated joint, in URDF order (``none`` choices included)."""
    commands = {joint.name: joint.commands for joint in control.joints if joint.commands}
    transmitted = {t.joint: t.interfaces for t in control.transmissions if t.commands()}
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
            # how the joint should be driven without one, so the default type applies - but a
            # continuous joint commanded by velocity is a wheel.
            kind, source = _default_type(joint, settings), "transmission"
            velocity = any("velocity" in i.lower() for i in transmitted[joint.name])
            if joint.kind == "continuous" and velocity:
                kind = "velocity"
        else:
            kind, source = _default_type(joint, settings), "default"
        choice = resolve_choice(
            joint.name,
            kind,
            source,
            settings,
            index,
            rule,
            _effort_range(joint),
            positive_velocity(joint),
        )
        if joint.name in commands:
            choice = replace(choice, runtime_commanded=True)
        if source in ("default", "transmission") and kind == "position" and _revolves(joint):
            choice = replace(choice, wheel_candidate=True)
        choices.append(choice)
    return choices


def check_rules(robot: Robot, settings: ActuatorSettings, manifest_label: str) -> None:
    """Refuse an actuator rule whose patterns match no actuated joint (always a typo)."""
    names = [joint.name for joint in actuated_joints(robot)]
    for index, rule in enumerate(settings.rules):
        if not any(matches(name, rule.joints) for name in names):
            named = next((j for j in robot.joints if matches(j.name, rule.joints)), None)
            if named is not None:  # a joint of the robot, which no actuator drives: say why
                raise ManifestError(
                    f"rule matches no actuated joint: {not_actuated(named)}",
                    file=f"{manifest_label} actuators.rules[{index}].joints",
                    hint=_instead(named, names),
                )
            raise ManifestError(
                f"rule matches no actuated joint ({', '.join(rule.joints)})"
                f"{suggestion(rule.joints, names)}",
                file=f"{manifest_label} actuators.rules[{index}].joints",
                hint=f"actuated joints: {listing(names)}",
            )


def not_actuated(joint: Joint) -> str:
    """Why ``joint``, a joint of the robot, has no actuator of its own."""
    if joint.mimic is not None:
        return (
            f"'{joint.name}' is a mimic follower: its leader '{joint.mimic.joint}' drives it "
            "through a joint equality, and it has no actuator of its own"
        )
    if not joint.moves:
        return f"'{joint.name}' is a fixed joint, which nothing moves"
    return f"'{joint.name}' is a {joint.kind} joint, which no one-axis actuator drives"


def _instead(joint: Joint, actuated: list[str]) -> str:
    """What to write instead of ``joint`` in an actuator rule."""
    if joint.mimic is not None:
        return f"name its leader '{joint.mimic.joint}' instead: its actuator moves both"
    return f"remove it from the rule; actuated joints: {listing(actuated)}"


def _first_rule(name: str, rules: list[ActuatorRule]) -> tuple[int | None, ActuatorRule | None]:
    for index, rule in enumerate(rules):
        if matches(name, rule.joints):
            return index, rule
    return None, None


def _preference(command: str) -> int:
    return _COMMAND_PREFERENCE.index(command) if command in _COMMAND_PREFERENCE else 99


def _revolves(joint: Joint) -> bool:
    """A continuous joint, or a revolute one without bounds (some descriptions draw wheels
    so), or with placeholder bounds (+-1e16)."""
    from mjcfbuild.urdf.limits import joint_range

    if joint.kind == "continuous":
        return True
    bounds = joint_range(joint)
    return joint.kind == "revolute" and (bounds is None or placeholder_range(bounds))


def _default_type(joint: Joint, settings: ActuatorSettings) -> str:
    return settings.default


def _effort_range(joint: Joint) -> tuple[float, float] | None:
    effort = joint.limit.effort if joint.limit is not None else None
    return (-effort, effort) if effort is not None and effort > 0 else None


def positive_velocity(joint: Joint) -> float | None:
    """The joint's URDF velocity limit where it is one (positive), else None."""
    velocity = joint.limit.velocity if joint.limit is not None else None
    return velocity if velocity is not None and velocity > 0 else None
