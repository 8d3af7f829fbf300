"""Real drives: what a motor's datasheet values make of the joint it moves.

From a motor (see :mod:`mjcfbuild.manifest.motors`), with gear ratio N:

- joint ``armature`` = rotor inertia x N^2 (the rotor's inertia reflected through the gearbox);
- the force limit = the peak torque at the output (rotor-side torques x N);
- a torque-speed line: at speed w the drive gives at most stall x (1 - |w| / w0), w0 the no-load
  speed at the output (rotor-side speeds / N). A position servo with such a line is written as
  MuJoCo 4.0's ``<dcmotor input="pos">`` (:mod:`mjcfbuild.actuators`), whose torque falls
  along the motor's line as speed rises;
- joint ``frictionloss`` and ``damping`` from the motor's friction and damping.

The gear ratio is the joint's ``<transmission>`` mechanicalReduction (ROS 1) or
``mechanical_reduction`` (ros2_control) where the URDF gives one, else the motor's ``ratio``,
else 1. A reduction on a joint no motor drives is reported, never dropped silently.
"""

from __future__ import annotations

import dataclasses
from dataclasses import asdict, dataclass

from mjcfbuild.actuators import ActuatorChoice
from mjcfbuild.inputs.ros2_control import Transmission
from mjcfbuild.manifest.simulation import ActuatorRule

# The supply voltage written into a <dcmotor> whose datasheet gives none: only the torque-speed
# line (stall torque and no-load speed) matters to the model, and MuJoCo derives the motor
# constant and resistance from the voltage in proportion.
UNIT_VOLTAGE = 1.0


@dataclass(frozen=True)
class Drive:
    """A motor as seen from the joint it moves: every value at the output."""

    motor: str
    ratio: float
    ratio_from: str  # transmission, motor, or default (1)
    armature: float
    peak_torque: float
    continuous_torque: float | None
    stall_torque: float | None  # the torque-speed line's torque at zero speed
    no_load_speed: float | None  # rad/s; None: no torque-speed line
    voltage: float
    friction: float | None
    damping: float | None

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)


def output_drive(name: str, motor: dict, reduction: float | None) -> Drive:
    """The drive of motor ``name`` (its datasheet values, as ``resolve_motors`` gives them) at
    the output of a gearbox of ``reduction`` (a transmission's), else of its own ratio."""
    if reduction is not None:
        ratio, source = reduction, "transmission"
    elif motor.get("ratio") is not None:
        ratio, source = float(motor["ratio"]), "motor"
    else:
        ratio, source = 1.0, "default"
    # Torques grow and speeds shrink through the gearbox when they are given at the rotor.
    torque = ratio if motor.get("at") == "rotor" else 1.0
    speed = 1 / ratio if motor.get("at") == "rotor" else 1.0
    stall, no_load = motor.get("stall_torque"), motor.get("no_load_speed")
    constant, resistance, voltage = (
        motor.get("torque_constant"),
        motor.get("resistance"),
        motor.get("voltage"),
    )
    if constant is not None and resistance is not None and voltage is not None:
        stall = stall if stall is not None else constant * voltage / resistance
        no_load = no_load if no_load is not None else voltage / constant
    if no_load is not None and stall is None:
        stall = motor["peak_torque"]
    return Drive(
        motor=name,
        ratio=ratio,
        ratio_from=source,
        armature=float(motor["rotor_inertia"]) * ratio**2,
        peak_torque=float(motor["peak_torque"]) * torque,
        continuous_torque=_scaled(motor.get("continuous_torque"), torque),
        stall_torque=_scaled(stall, torque),
        no_load_speed=_scaled(no_load, speed),
        voltage=float(voltage) if voltage is not None else UNIT_VOLTAGE,
        friction=motor.get("friction"),
        damping=motor.get("damping"),
    )


def _scaled(value: float | None, factor: float) -> float | None:
    return None if value is None else float(value) * factor


def underactuated(
    transmissions: list[Transmission], actuated: set[str]
) -> list[list[Transmission]]:
    """The transmissions (one per joint, in the URDF's order) of each mechanism that moves
    more of the ``actuated`` joints than it has actuators: transmissions linked by one
    ``<transmission>`` element or by an actuator name they share, where some joint is only
    read (a state interface: TIAGo's Hey5 hand moves 22 finger joints by one motor and
    commands one of them) or one element holds more joints than actuators. Several
    transmissions naming one actuator but each commanding its joint are a copied name (a
    pybullet xArm's two joints on ``motor3``), not a mechanism; a differential (two motors,
    two joints) is fully actuated."""
    group = list(range(len(transmissions)))  # union-find over the transmissions

    def root(index: int) -> int:
        while group[index] != index:
            group[index] = group[group[index]]
            index = group[index]
        return index

    first: dict[str, int] = {}
    for index, transmission in enumerate(transmissions):
        element = [f"element {transmission.element}"] if transmission.element else []
        for key in [*element, *transmission.actuators]:
            group[root(index)] = root(first.setdefault(key, index))
    linked: dict[int, list[Transmission]] = {}
    for index, transmission in enumerate(transmissions):
        linked.setdefault(root(index), []).append(transmission)
    found = []
    for members in linked.values():
        joints: dict[str, Transmission] = {}
        for transmission in members:
            if transmission.joint in actuated:
                joints.setdefault(transmission.joint, transmission)
        names = {name for transmission in members for name in transmission.actuators}
        read_only = any(not transmission.commands() for transmission in members)
        if len(joints) > max(len(names), 1) and (read_only or _crowded(members)):
            found.append(list(joints.values()))
    return found


def _crowded(members: list[Transmission]) -> bool:
    """Whether one ``<transmission>`` element among ``members`` holds more joints than
    actuators (each of its joints' records carries the element's actuators)."""
    elements: dict[str, list[Transmission]] = {}
    for transmission in members:
        if transmission.element:
            elements.setdefault(transmission.element, []).append(transmission)
    return any(len(joints) > len(joints[0].actuators) for joints in elements.values())


def reductions(
    transmissions: list[Transmission], mechanisms: list[list[Transmission]]
) -> dict[str, Transmission]:
    """Joint -> the transmission that gives its gear ratio (the first one that does); not
    the joints one of the underactuated ``mechanisms`` only reads (:func:`underactuated`),
    whose reductions are ratios between its joints."""
    followers = {t.joint for mechanism in mechanisms for t in mechanism if not t.commands()}
    found: dict[str, Transmission] = {}
    for transmission in transmissions:
        joint = transmission.joint
        if transmission.reduction is not None and joint not in found and joint not in followers:
            found[joint] = transmission
    return found


def apply_motors(
    choices: list[ActuatorChoice],
    rules: list[ActuatorRule],
    motors: dict[str, dict],
    transmissions: list[Transmission],
) -> tuple[list[ActuatorChoice], list[str]]:
    """``choices`` with their rules' motors applied (armature, force limits, torque-speed
    line, friction, damping; what the rule itself sets wins), and the build's warnings: a
    transmission's reduction that no motor uses, and a reduction that overrides a motor's own
    ratio."""
    mechanisms = underactuated(transmissions, {choice.joint for choice in choices})
    geared = reductions(transmissions, mechanisms)
    warnings: list[str] = []
    result = []
    used: set[str] = set()
    for choice in choices:
        rule = rules[choice.rule] if choice.rule is not None else None
        if rule is None or rule.motor is None or choice.type in ("none", "user"):
            result.append(choice)
            continue
        transmission = geared.get(choice.joint)
        reduction = transmission.reduction if transmission else None
        drive = output_drive(rule.motor, motors[rule.motor], reduction)
        if transmission is not None:
            used.add(choice.joint)
            own = motors[rule.motor].get("ratio")
            if own is not None and abs(float(own) - drive.ratio) > 1e-9 * drive.ratio:
                warnings.append(
                    f"joint '{choice.joint}': the <transmission> reduction {drive.ratio:g} "
                    f"({transmission.origin}) replaces the ratio {own:g} of motor '{rule.motor}'"
                )
        result.append(_driven(choice, rule, drive))
    warnings += [_mechanism_warning(mechanism) for mechanism in mechanisms]
    actuated = {choice.joint for choice in choices}
    for joint, transmission in sorted(geared.items()):
        # Only a joint an actuator drives can take a motor (one the URDF lacks is the plan's
        # warning, and a rule naming a fixed or mimic joint is refused).
        if joint not in used and joint in actuated:
            warnings.append(
                f"{transmission.origin}: joint '{joint}' has a <transmission> reduction of "
                f"{transmission.reduction:g} but no motor, so it sets nothing; name the drive "
                f'in a rule (actuators: {{rules: [{{joints: ["{joint}"], motor: NAME}}]}})'
            )
    return result, warnings


def _mechanism_warning(mechanism: list[Transmission]) -> str:
    """What the model does with joints fewer actuators move together, and how to couple them."""
    types = ", ".join(sorted({t.kind for t in mechanism if t.kind})) or "unnamed"
    names = ", ".join(sorted({n for t in mechanism for n in t.actuators})) or "none named"
    return (
        f"{mechanism[0].origin}: <transmission>s of type '{types}' move {len(mechanism)} "
        f"joints from '{mechanism[0].joint}' by actuator '{names}': an underactuated "
        "mechanism the model does not reproduce - each joint moves on its own, and the "
        "reductions of those it only reads set nothing; to move them together, give them "
        "<equality><joint joint1=... joint2=... polycoef=.../> in the raw inputs"
    )


def _driven(choice: ActuatorChoice, rule: ActuatorRule, drive: Drive) -> ActuatorChoice:
    peak = drive.peak_torque
    return dataclasses.replace(
        choice,
        armature=rule.armature if rule.armature is not None else drive.armature,
        forcerange=rule.forcerange or (-peak, peak),
        effort_limited=False,
        damping=rule.damping if rule.damping is not None else drive.damping,
        frictionloss=rule.frictionloss if rule.frictionloss is not None else drive.friction,
        motor=drive.to_dict(),
    )


# The name a drive made from the URDF's own limits goes by in the report and check.json.
URDF_LIMITS = "URDF limits"


def urdf_drive(effort: float, velocity: float, timestep: float) -> Drive:
    """The drive a joint's URDF limits describe when no motor is named: the torque-speed line
    from its effort (at standing still) to its velocity limit (at no load), on the rotor
    inertia that keeps that line stable at ``timestep`` (:func:`line_inertia`). A URDF gives
    the joint's top speed and torque, and a DC drive's torque falls along such a line between
    them; with it a default servo moves no faster than the real joint."""
    return Drive(
        motor=URDF_LIMITS,
        ratio=1.0,
        ratio_from="default",
        armature=line_inertia(effort, velocity, timestep),
        peak_torque=effort,
        continuous_torque=None,
        stall_torque=effort,
        no_load_speed=velocity,
        voltage=UNIT_VOLTAGE,
        friction=None,
        damping=None,
    )


# A DC drive's mechanical time constant (rotor inertia x no-load speed / stall torque, the time
# its line takes to brake the rotor) in time steps at least. MuJoCo applies the line's torque at
# the speed the step starts with: at 1 step the rotor's speed settles in one step, past 1 it
# rings and past 2 it diverges. Real gearmotors take 5-30 ms (2.5-15 steps of 2 ms).
LINE_STEPS = 1.0


def line_inertia(stall_torque: float, no_load_speed: float, timestep: float) -> float:
    """The rotor inertia that keeps a torque-speed line stable at ``timestep``: the line brakes
    like a damper of stall torque / no-load speed, which the step applies explicitly. A rotor
    of this inertia is there in every pose, unlike the link's."""
    return LINE_STEPS * timestep * stall_torque / no_load_speed
