"""The home pose: a position for every moving joint.

Each joint takes the first of: the first ``home:`` pattern in robot.yaml that matches it, the
SRDF's ``<group_state name="home">``, its ros2_control ``initial_value``, an MJCF part's own
home (``fallback``), and 0 - clipped into the joint's range. A mimic follower sits where its
equality puts it.
"""

from __future__ import annotations

from dataclasses import dataclass

from mjcfbuild.control.choose import matches
from mjcfbuild.errors import ManifestError
from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.sources.packages import listing, suggestion
from mjcfbuild.urdf.limits import joint_range
from mjcfbuild.urdf.model import Joint, Robot


@dataclass(frozen=True)
class HomeValue:
    """One joint's home position and where it came from."""

    joint: str
    value: float
    source: str  # robot.yaml, srdf, ros2_control, part, zero, mimic


def home_values(
    robot: Robot,
    control: Ros2Control,
    patterns: dict[str, float],
    srdf_state: dict[str, float] | None = None,
    manifest_label: str = "robot.yaml",
    fallback: dict[str, float] | None = None,
) -> list[HomeValue]:
    """The home position of every moving joint, in URDF order. ``fallback`` gives joints of
    MJCF parts their part's own home. A floating joint has none: its position is the base's
    pose, which the assembly stands on the floor."""
    moving = [joint for joint in robot.joints if joint.moves and joint.kind != "floating"]
    _check_patterns(moving, patterns, manifest_label, robot.joints)
    initial = {j.name: j.initial for j in control.joints if j.initial is not None}
    srdf_state = srdf_state or {}
    values: dict[str, HomeValue] = {}
    for joint in moving:
        if joint.mimic is not None:
            continue
        pattern = next((p for p in patterns if matches(joint.name, [p])), None)
        if pattern is not None:
            value, source = patterns[pattern], "robot.yaml"
        elif joint.name in srdf_state:
            value, source = srdf_state[joint.name], "srdf"
        elif joint.name in initial:
            value, source = initial[joint.name], "ros2_control"
        elif fallback and joint.name in fallback:
            value, source = fallback[joint.name], "part"
        else:
            value, source = 0.0, "zero"
        values[joint.name] = HomeValue(joint.name, _clip(value, joint), source)
    for joint in moving:
        if joint.mimic is not None:
            values[joint.name] = HomeValue(joint.name, _mimic_value(joint, robot, values), "mimic")
    return [values[joint.name] for joint in moving]


def _mimic_value(joint: Joint, robot: Robot, values: dict[str, HomeValue]) -> float:
    """multiplier * leader + offset, following chains of mimics."""
    joints = {j.name: j for j in robot.joints}
    seen = {joint.name}
    assert joint.mimic is not None
    leader, multiplier, offset = joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset
    while leader not in values and leader not in seen:
        step = joints[leader].mimic
        if step is None:
            break
        seen.add(leader)
        leader, multiplier, offset = (
            step.joint,
            multiplier * step.multiplier,
            multiplier * step.offset + offset,
        )
    base = values[leader].value if leader in values else 0.0
    return multiplier * base + offset


def _no_home(joint: Joint) -> str:
    """Why ``joint``, a joint of the robot that is not a moving one, has no home value."""
    if not joint.moves:
        return f"'{joint.name}' is a fixed joint, which has no position to set"
    return (
        f"'{joint.name}' is a floating joint: its position is the base's pose, which the build "
        "stands on the floor"
    )


def _clip(value: float, joint: Joint) -> float:
    bounds = joint_range(joint)
    if bounds is None:
        return value
    return min(max(value, bounds[0]), bounds[1])


def _check_patterns(
    moving: list[Joint], patterns: dict[str, float], label: str, joints: list[Joint]
) -> None:
    """Every pattern names a moving joint, and its value lies in the range of each it names;
    one naming only a joint with no home (fixed, floating: among ``joints``) says so."""
    names = [joint.name for joint in moving]
    for pattern, value in patterns.items():
        named = [joint for joint in moving if matches(joint.name, [pattern])]
        other = next((j for j in joints if matches(j.name, [pattern])), None)
        if not named and other is not None:
            said = "" if pattern == other.name else f"'{pattern}' matches no moving joint: "
            raise ManifestError(
                f"{said}{_no_home(other)}",
                file=f"{label} home.{pattern}",
                hint=f"remove it; moving joints: {listing(names)}",
            )
        if not named:
            raise ManifestError(
                f"'{pattern}' matches no moving joint{suggestion([pattern], names)}",
                file=f"{label} home.{pattern}",
                hint=f"moving joints: {listing(names)}",
            )
        for joint in named:
            bounds = joint_range(joint)
            if joint.mimic is not None and pattern == joint.name:
                raise ManifestError(
                    f"joint '{joint.name}' mimics '{joint.mimic.joint}'; its home follows",
                    file=f"{label} home.{pattern}",
                    hint=f"set the home of '{joint.mimic.joint}' instead",
                )
            if joint.mimic is None and bounds is not None and not bounds[0] <= value <= bounds[1]:
                raise ManifestError(
                    f"{value:g} is outside the range of joint '{joint.name}' "
                    f"[{bounds[0]:g}, {bounds[1]:g}]",
                    file=f"{label} home.{pattern}",
                    hint="give a value within the joint's limits",
                )
