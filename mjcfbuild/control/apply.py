"""Writing actuators, joint dynamics, the home keyframe and the floating base's height into the
model tree.

Gains given as a natural frequency need the joint's effective inertia, which only the compiled
model knows: the diagonal of the joint-space inertia matrix at home, armature included. So the
tree is compiled once with the joint dynamics in place, gains and heights are computed from that
model, and the caller compiles the finished tree again.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from copy import deepcopy
from dataclasses import asdict, dataclass, field, replace
from typing import Any

from lxml import etree

from mjcfbuild.actuators import (
    ACTUATOR_TAGS,
    NONE,
    POSITION,
    POSITION_KINDS,
    USER,
    VELOCITY,
    ActuatorChoice,
    ActuatorRecord,
    actuator_attributes,
    actuator_record,
    has_speed_line,
    is_dcmotor,
    settle_kind,
)
from mjcfbuild.control.choose import limit_notes, placeholder_range, positive_velocity
from mjcfbuild.control.efforts import EffortCap, describe, placeholder_efforts
from mjcfbuild.control.floor import lowest_collision_point, lowest_visual_point
from mjcfbuild.control.home import HomeValue
from mjcfbuild.control.motors import URDF_LIMITS, urdf_drive
from mjcfbuild.control.rotors import describe as describe_rotor
from mjcfbuild.control.rotors import heavy_rotor
from mjcfbuild.control.standing import MARGIN
from mjcfbuild.numbers import output_list
from mjcfbuild.urdf.limits import joint_range
from mjcfbuild.urdf.model import Robot

HOME = "home"


@dataclass
class Readiness:
    """What :func:`make_ready` did, for the report and the check."""

    actuators: list[ActuatorRecord] = field(default_factory=list)
    passive: list[str] = field(default_factory=list)  # joints with actuator type none
    home: list[dict] = field(default_factory=list)
    home_written: bool = False
    base_height: float | None = None  # how far a floating base was raised to stand
    # the lowest collision point at home (fixed base); the lowest visual one, marked
    # "visual", where nothing collides
    lowest_point: dict | None = None
    stance: dict | None = None  # how a floating robot meets the floor at home
    home_from: str | None = None  # the SRDF group_state home's "srdf" values come from
    notes: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)


def user_driven_joints(root: etree._Element) -> set[str]:
    """Joints an actuator already in the tree drives (written by the user), directly or
    through a fixed tendon."""
    section = root.find("actuator")
    if section is None:
        return set()
    tendons = {
        tendon.get("name"): {j.get("joint") for j in tendon.findall("joint")}
        for tendon in root.iter("fixed")
    }
    driven: set[str] = set()
    for element in section:
        if element.tag not in ACTUATOR_TAGS:
            continue
        joint = element.get("joint") or element.get("jointinparent")
        if joint:
            driven.add(joint)
        driven |= tendons.get(element.get("tendon"), set())
    return driven


def _without_actuator_state(root: etree._Element) -> etree._Element:
    """``root``, or a copy of it whose keyframes hold no ``ctrl`` or ``act``: an input's
    keyframe gives them for the finished model's actuators, which the compiles before the
    actuators are added do not have yet (MuJoCo said "expected length 0")."""
    if not any("ctrl" in key.attrib or "act" in key.attrib for key in root.iter("key")):
        return root
    copy = deepcopy(root)
    for key in copy.iter("key"):
        key.attrib.pop("ctrl", None)
        key.attrib.pop("act", None)
    return copy


def make_ready(
    root: etree._Element,
    robot: Robot,
    choices: list[ActuatorChoice],
    home: list[HomeValue],
    floating: bool,
    compile_tree: Callable[[etree._Element], Any],
    preset_qpos: dict[str, list[float]] | None = None,
    preset_ctrl: dict[str, float] | None = None,
    forcerange_at: Sequence[str] = (),
) -> Readiness:
    """Add actuators, joint dynamics and the home keyframe to ``root``; stand a floating base on
    the floor. ``compile_tree`` turns the tree into an ``MjModel``. ``preset_qpos`` and
    ``preset_ctrl`` are MJCF parts' own home: the qpos of joints ``home`` does not set (ball
    joints) and the ctrl of actuators not driving a joint directly (see _preset_ctrl).
    ``forcerange_at`` is where robot.yaml writes each actuators rule's forcerange
    (``robot.yaml:5: actuators.rules[0].forcerange``), for the warnings that name it."""
    import mujoco
    import numpy as np

    readiness = Readiness(home=[asdict(value) for value in home])
    readiness.notes += limit_notes(robot)
    joints = {element.get("name"): element for element in root.iter("joint")}
    bodies = {element.get("name"): element for element in root.iter("body")}
    urdf_joints = {joint.name: joint for joint in robot.joints}
    for choice in choices:
        _set_dynamics(joints.get(choice.joint), choice)
        _set_force_limit(joints.get(choice.joint), choice, urdf_joints[choice.joint])
        if choice.gravcomp and urdf_joints[choice.joint].child in bodies:
            bodies[urdf_joints[choice.joint].child].set("gravcomp", "1")
    generated = [c for c in choices if c.type not in (NONE, USER)]
    readiness.notes += runtime_line_notes(generated)
    readiness.passive = [c.joint for c in choices if c.type == NONE]
    if generated and not _has_integrator(root):
        # Stiff servos on light links need the implicit treatment of actuator damping that
        # MuJoCo Menagerie's models use; the default Euler integrator treats it explicitly.
        option = root.find("option")
        if option is None:
            option = etree.Element("option")
            root.insert(1, option)
        option.set("integrator", "implicitfast")

    model = compile_tree(_without_actuator_state(root))
    _planar_joints(model, robot, readiness)
    data = mujoco.MjData(model)
    qpos = _home_qpos(model, home, preset_qpos)
    if floating:
        readiness.base_height = _stand_on_floor(root, model, data, qpos)
        if readiness.base_height is not None and not _move_free_bodies(model, data, root):
            model = compile_tree(_without_actuator_state(root))
            data = mujoco.MjData(model)
        qpos = _home_qpos(model, home, preset_qpos)
    data.qpos[:] = qpos
    mujoco.mj_forward(model, data)
    if not floating:
        lowest = lowest_collision_point(model, data)
        if lowest is not None:
            readiness.lowest_point = {"height": lowest.height, "body": lowest.body}
        else:  # nothing collides: the floor goes under what is drawn, not through it
            drawn = lowest_visual_point(model, data)
            if drawn is not None:
                readiness.lowest_point = {
                    "height": drawn.height,
                    "body": drawn.body,
                    "visual": True,
                }
    choices = _drive_wheels(model, data, choices)
    inertia = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, inertia)
    bias = standing_torques(model, data) if floating else data.qfrc_bias
    caps = _effort_caps(model, data, generated, readiness) if floating else {}
    pendulum = _pendulum(model, data, readiness) if floating else None

    section = root.find("actuator")
    if section is None and generated:
        section = etree.SubElement(root, "actuator")
    taken = {e.get("name") for e in section} if section is not None else set()
    for choice in choices:
        if choice.type == USER:
            readiness.actuators.append(ActuatorRecord("", choice.joint, USER, USER))
            continue
        if choice.type == NONE:
            continue
        motion = _coupled_motion(model, choice.joint, robot)
        moved = float(motion @ inertia @ motion)
        if not moved > 0:
            _unresolved_inertia(robot, urdf_joints[choice.joint], moved)
        servo = Servo(
            moved,
            abs(float(motion @ bias)),
            model.opt.timestep,
            *(_carried(pendulum, motion) if pendulum is not None else (0.0, 0.0)),
            reach=max(1.0, float(np.abs(motion).max())),
        )
        record = _actuator(choice, urdf_joints[choice.joint], servo, taken, caps.get(choice.joint))
        taken.add(record.name)
        readiness.actuators.append(record)
        readiness.notes += _heavy_rotor(
            model,
            data,
            record,
            choice,
            servo,
            robot,
            _forcerange_of(choice, choices, forcerange_at),
        )
    _match_mirrored(model, data, readiness.actuators)
    for record in readiness.actuators:
        if record.source != USER:
            etree.SubElement(section, record.type, actuator_attributes(record))
        if record.armature is not None and record.joint in joints:
            # Added to what each joint has (its URDF's or a default class's), which the inertia
            # the gains were sized for already holds; shared along the coupled motion, so a
            # mimic follower (a finger's light distal link) is not left without the rotor
            # inertia its leader got, and chatters against its equality at tens of rad/s.
            shares = _armature_shares(model, record.joint, robot, record.armature)
            for name, share in shares.items():
                if name in joints:
                    own = _joint_armature(model, name)
                    joints[name].set("armature", output_list([own + share]))
            record.armature = shares[record.joint]
    _fill_user_records(readiness, root)

    if _has_key(root, HOME):
        readiness.notes.append("the inputs define a 'home' keyframe; it is kept as written")
        return readiness
    final = compile_tree(root)
    final_data = mujoco.MjData(final)
    final_data.qpos[:] = _home_qpos(final, home, preset_qpos)
    mujoco.mj_forward(final, final_data)
    torques = standing_torques(final, final_data) if floating else final_data.qfrc_bias
    ctrl = _home_ctrl(final, final_data, torques)
    _preset_ctrl(final, final_data, ctrl, preset_ctrl or {})
    keyframe = root.find("keyframe")
    if keyframe is None:
        keyframe = etree.SubElement(root, "keyframe")
    attributes = {"name": HOME, "qpos": output_list(final_data.qpos)}
    if final.nu:
        attributes["ctrl"] = output_list(ctrl)
    if final.na:
        attributes["act"] = output_list(_home_act(final, final_data))
    keyframe.insert(0, etree.Element("key", attributes))
    readiness.home_written = True
    return readiness


def standing_torques(model, data, tolerance: float = 2e-3):
    """Joint torques that hold a floating robot standing at ``data``'s pose: gravity, less the
    robot's weight shared equally by the bodies whose collision geometry touches the floor
    (z = 0), each pushing up at its lowest point."""
    import mujoco
    import numpy as np

    from mjcfbuild.control.floor import geom_lowest_points

    points = geom_lowest_points(model, data)
    feet: dict[int, np.ndarray] = {}
    for geom, point in points.items():
        body = int(model.geom_bodyid[geom])
        if point[2] <= tolerance and body not in feet:
            feet[body] = point
    torques = data.qfrc_bias.copy()
    if not feet:
        return torques
    weight = float(model.body_subtreemass[0]) * float(np.linalg.norm(model.opt.gravity))
    jacobian = np.zeros((3, model.nv))
    for body, point in feet.items():
        mujoco.mj_jac(model, data, jacobian, None, point, body)
        torques -= jacobian.T @ np.array([0.0, 0.0, weight / len(feet)])
    return torques


def _planar_joints(model, robot: Robot, readiness: Readiness) -> None:
    """A URDF planar joint is three MuJoCo joints (<name>_TX, _TY, _RZ): no generated servo
    drives them (like a free joint), so they are passive, and the build says so."""
    import mujoco

    for joint in robot.joints:
        if joint.kind != "planar":
            continue
        parts = [f"{joint.name}_{suffix}" for suffix in ("TX", "TY", "RZ")]
        found = [n for n in parts if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, n) >= 0]
        readiness.passive += found
        readiness.notes.append(
            f"planar joint '{joint.name}' (URDF line {joint.line}) is {', '.join(found)} in "
            "the model: no actuator is generated for them (a base moved by a controller); "
            "drive them with actuators of your own in mujoco_inputs.raw, e.g. "
            f'<velocity joint="{found[0] if found else joint.name}" kv="100"/>'
        )


def _set_force_limit(element, choice: ActuatorChoice, joint) -> None:
    """The joint's own force limit: a rule's forcerange, else none where the URDF's effort is
    not a limit (MuJoCo's import makes effort="-1" a limit of 1)."""
    if element is None:
        return
    if choice.rule_forcerange and choice.forcerange is not None:
        element.set("actuatorfrcrange", output_list(list(choice.forcerange)))
    elif joint.limit is not None and joint.limit.effort is not None and joint.limit.effort <= 0:
        element.attrib.pop("actuatorfrcrange", None)


def _drive_wheels(model, data, choices: list[ActuatorChoice]) -> list[ActuatorChoice]:
    """Wheel candidates whose geometry is a wheel on the floor get velocity servos."""
    from mjcfbuild.control.wheels import wheel_joints

    candidates = [choice.joint for choice in choices if choice.wheel_candidate]
    if not candidates:
        return choices
    wheels = wheel_joints(model, data, candidates)
    return [
        replace(choice, type=VELOCITY, source="wheel") if choice.joint in wheels else choice
        for choice in choices
    ]


def _pendulum(model, data, readiness: Readiness):
    """The gravity stiffness and carried inertia per DOF of a floating robot at home (see
    control.standing); records how it stands."""
    from mjcfbuild.control.standing import pendulum_loads, rolling_bodies, stance

    found = stance(model, data, rolling_bodies(model, data))
    readiness.stance = {
        "feet": sorted(mujoco_name(model, "body", body) for body in found.feet),
        "area": found.area,
        "com_margin": found.margin,
        "can_stand": found.can_stand,
        "why_not": found.why_not(),
    }
    return pendulum_loads(model, data, found.feet)


def mujoco_name(model, kind: str, index: int) -> str:
    """The name of MuJoCo object ``index`` of ``kind`` (body, joint, ...), or '#index'."""
    import mujoco

    kinds = {"body": mujoco.mjtObj.mjOBJ_BODY, "joint": mujoco.mjtObj.mjOBJ_JOINT}
    return mujoco.mj_id2name(model, kinds[kind], index) or f"#{index}"


def _carried(pendulum, motion) -> tuple[float, float]:
    stiffness, carried = pendulum
    return float(abs(motion) @ stiffness), float((motion * motion) @ carried)


def _coupled_motion(model, joint: str, robot: Robot):
    """The joint-space direction that moving ``joint`` by one unit moves: 1 at its own DOF and
    each mimic follower's multiplier at theirs (followers of followers too), so a leader's
    servo is sized for the inertia and load of everything it moves."""
    import mujoco
    import numpy as np

    motion = np.zeros(model.nv)
    for name, factor in _coupled_factors(model, joint, robot).items():
        motion[model.jnt_dofadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)]] = factor
    return motion


def _coupled_factors(model, joint: str, robot: Robot) -> dict[str, float]:
    """How far each joint of the model moves when ``joint`` moves by one unit: 1 for itself,
    its mimic followers' multipliers (followers of followers too); hinges and slides only."""
    import mujoco

    factors = {joint: 1.0}
    changed = True
    while changed:
        changed = False
        for follower in robot.joints:
            mimic = follower.mimic
            if mimic is None or follower.name in factors or mimic.joint not in factors:
                continue
            factors[follower.name] = factors[mimic.joint] * mimic.multiplier
            changed = True
    kept = {}
    for name, factor in factors.items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if index >= 0 and mujoco.mjtJoint(model.jnt_type[index]) in (
            mujoco.mjtJoint.mjJNT_HINGE,
            mujoco.mjtJoint.mjJNT_SLIDE,
        ):
            kept[name] = factor
    return kept


def _armature_shares(model, joint: str, robot: Robot, added: float) -> dict[str, float]:
    """The armature each joint of ``joint``'s coupled motion gets of ``added``: the same on
    each, so that along the motion the servo was sized for they add up to ``added`` (a joint
    moved f times as far counts f^2 times)."""
    factors = _coupled_factors(model, joint, robot) or {joint: 1.0}
    total = sum(factor * factor for factor in factors.values())
    share = added / total if total > 0 else added
    return {name: share for name in factors} | {joint: share}


def _forcerange_of(
    choice: ActuatorChoice, choices: list[ActuatorChoice], forcerange_at: Sequence[str]
) -> tuple[str, bool] | None:
    """Where robot.yaml gives ``choice``'s forcerange (its rule's key path, with its line where
    known) and whether that rule drives other joints of ``choices`` too; None where the
    forcerange is the URDF's effort."""
    if not choice.rule_forcerange or choice.rule is None:
        return None
    index = choice.rule
    at = forcerange_at[index] if index < len(forcerange_at) else ""
    shared = any(other.rule == index and other.joint != choice.joint for other in choices)
    return at or f"actuators.rules[{index}].forcerange", shared


def _heavy_rotor(
    model,
    data,
    record: ActuatorRecord,
    choice: ActuatorChoice,
    servo: Servo,
    robot: Robot,
    rule: tuple[str, bool] | None = None,
) -> list[str]:
    """The warning about a joint whose speed line (from its URDF velocity, and its URDF effort
    or ``rule``'s forcerange: where robot.yaml gives it, and whether the rule drives other
    joints too) gave it a rotor no real drive of it could have (``control.rotors``); none for
    a named motor's or a rule's armature."""
    motor = record.motor or {}
    if motor.get("motor") != URDF_LIMITS or choice.armature is not None:
        return []
    joint = next((joint for joint in robot.joints if joint.name == choice.joint), None)
    if joint is None or not _all_weighed(robot, joint.child):
        return []  # placeholder masses say nothing of the rotor; the check names those links
    found = heavy_rotor(model, data, choice.joint, motor["armature"], servo.inertia)
    if found is None:
        return []
    where = f"{robot.source}:{joint.line}" if joint.line else robot.source
    effort, velocity = motor["stall_torque"], motor["no_load_speed"]
    if rule is None:
        return [describe_rotor(found, where, effort, velocity)]
    return [describe_rotor(found, where, effort, velocity, rule=rule[0], shared=rule[1])]


def _all_weighed(robot: Robot, link: str) -> bool:
    """Whether ``link`` and every link below it have a mass in the URDF."""
    links = {each.name: each for each in robot.links}
    below: dict[str, list[str]] = {}
    for joint in robot.joints:
        below.setdefault(joint.parent, []).append(joint.child)
    pending = [link]
    while pending:
        name = pending.pop()
        # A link of an attached MJCF part is in no URDF: its masses are the part's own.
        inertial = links[name].inertial if name in links else None
        if inertial is None or not inertial.mass > 0:
            return False
        pending += below.get(name, [])
    return True


def _unresolved_inertia(robot: Robot, joint, moved: float) -> None:
    """Refuse, at the joint's URDF line, a joint whose inertia at home MuJoCo computes as none
    or less (rounding: tiny masses against centres of mass kilometres away): no servo can be
    sized for it, and MuJoCo refuses the negative gains that would follow."""
    from mjcfbuild.errors import InputError

    raise InputError(
        f"joint '{joint.name}' moves an inertia MuJoCo computes as {moved:.3g} at home: the "
        "masses it moves are lost to rounding against the robot's extent",
        file=robot.source,
        line=joint.line,
        hint="check the <inertial> origins (a centre of mass kilometres from its link) and "
        "masses of the robot's links",
    )


def _match_mirrored(model, data, records: list[ActuatorRecord]) -> None:
    """Give joints that mirror each other across the base's sagittal plane the same gains
    (the larger of the two), so a left-right symmetric robot gets symmetric servos."""
    from mjcfbuild.control.standing import mirror_pairs

    generated = {r.joint: r for r in records if r.source != USER and r.type in POSITION_KINDS}
    for left, right in mirror_pairs(model, data, sorted(generated)):
        first, second = generated[left], generated[right]
        for attribute in ("kp", "kv", "armature"):
            values = [getattr(first, attribute), getattr(second, attribute)]
            if None in values:
                continue
            setattr(first, attribute, max(values))
            setattr(second, attribute, max(values))


def _joint_armature(model, joint: str) -> float:
    """The armature ``joint`` has in the compiled model (0 if it is not there)."""
    import mujoco

    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
    return float(model.dof_armature[model.jnt_dofadr[index]]) if index >= 0 else 0.0


def _set_dynamics(element, choice: ActuatorChoice) -> None:
    if element is None:
        return
    for attribute in ("armature", "damping", "frictionloss"):
        value = getattr(choice, attribute)
        if value is not None:
            element.set(attribute, output_list([value]))


def _has_integrator(root) -> bool:
    return any(option.get("integrator") for option in root.findall("option"))


def _has_key(root, name: str) -> bool:
    return any(key.get("name") == name for key in root.iter("key"))


def _home_qpos(model, home: list[HomeValue], preset: dict[str, list[float]] | None = None):
    import mujoco

    qpos = model.qpos0.copy()
    for name, values in (preset or {}).items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if index >= 0:
            address = model.jnt_qposadr[index]
            qpos[address : address + len(values)] = values
    for value in home:
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, value.joint)
        if index >= 0:
            qpos[model.jnt_qposadr[index]] = value.value
    return qpos


def _stand_on_floor(root, model, data, qpos) -> float | None:
    """Raise every free body so the lowest collision point at home touches z = 0; the raise."""
    import mujoco

    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    lowest = lowest_collision_point(model, data)
    if lowest is None:
        return None
    lift = -lowest.height
    for body in root.iter("body"):
        if body.find("freejoint") is not None or any(
            j.get("type") == "free" for j in body.findall("joint")
        ):
            position = [float(v) for v in (body.get("pos") or "0 0 0").split()]
            position[2] += lift
            body.set("pos", output_list(position))
    return lift


def _move_free_bodies(model, data, root) -> bool:
    """Give the compiled ``model`` its free bodies' positions from ``root`` (as
    :func:`_stand_on_floor` raised them): each body's position and its free joint's reference
    pose, then the constants MuJoCo derives from the reference pose, which is what compiling
    ``root`` again gives (a compile of g1 less) but for the statistics MuJoCo draws with.
    False, with ``model`` unchanged, where a compile could give more: a free body with no
    name to find it by or not in the world body itself (a frame would move it), keyframes
    (one without qpos takes the reference pose), tendons (a spring length taken from it),
    constraints other than between joints (a weld's pose taken from it)."""
    import mujoco

    if model.nkey or model.ntendon:
        return False
    if any(kind != mujoco.mjtEq.mjEQ_JOINT for kind in model.eq_type):
        return False
    moves = []
    for body in root.iter("body"):
        if body.find("freejoint") is None and not any(
            j.get("type") == "free" for j in body.findall("joint")
        ):
            continue
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body.get("name") or "")
        parent = body.getparent()
        if index < 0 or parent is None or parent.tag != "worldbody":
            return False
        free = [
            j
            for j in range(
                model.body_jntadr[index], model.body_jntadr[index] + model.body_jntnum[index]
            )
            if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE
        ]
        if len(free) != 1:
            return False
        position = [float(v) for v in (body.get("pos") or "0 0 0").split()]
        moves.append((index, model.jnt_qposadr[free[0]], position))
    for index, address, position in moves:
        model.body_pos[index] = position
        model.qpos0[address : address + 3] = position
        model.qpos_spring[address : address + 3] = position
    mujoco.mj_setConst(model, data)
    return True


# A weight-bearing servo's natural frequency times the time step at most (with armature added
# where the joint's own inertia is too small): above about 1 a biped's ankles ring and it falls.
STEP_RATIO = 0.5

# Default gains are stiffened until gravity at home bends a joint by at most this much (rad or
# m): a servo tuned by frequency alone lets a light link on a short lever sag by g / (r w^2).
SAG = 0.01


@dataclass(frozen=True)
class Servo:
    """What a joint's servo gains are worked out from: its effective inertia at home, the
    gravity load it holds there, and the time step (which bounds a stable stiffness)."""

    inertia: float
    load: float
    timestep: float
    pendulum: float = 0.0  # gravity stiffness of what the joint carries standing (N m/rad)
    carried: float = 0.0  # inertia of what the joint carries standing (kg m^2)
    reach: float = 1.0  # the largest mimic multiplier: a follower moves this much more

    @property
    def sag(self) -> float:
        """The sag allowed at this joint, so that no follower sags more than SAG."""
        return SAG / self.reach

    def omega(self, frequency: float, stiffen: bool) -> float:
        """The natural frequency (rad/s) of the servo."""
        omega = 2 * math.pi * frequency
        if stiffen and self.inertia > 0:
            # Never above a quarter of the step rate, where the implicit integrator stays accurate.
            ceiling = 0.5 / self.timestep
            omega = max(omega, min(math.sqrt(self.load / (self.sag * self.inertia)), ceiling))
        return omega


def _effort_caps(
    model, data, generated: list[ActuatorChoice], readiness: Readiness
) -> dict[str, EffortCap]:
    """A floating robot's placeholder efforts (joint -> the holding load that replaces them),
    noted in ``readiness``; empty where the URDF's efforts are plausible."""
    efforts = {
        choice.joint: choice.forcerange[1]
        for choice in generated
        if choice.effort_limited and choice.forcerange
    }
    caps = placeholder_efforts(model, data, efforts)
    if caps:
        readiness.notes.append(describe(caps))
    return {cap.joint: cap for cap in caps}


# A velocity servo's kv over the joint's damping: it then reaches 98 % of a commanded speed.
VELOCITY_TRACKING = 49.0


def _actuator(
    choice: ActuatorChoice,
    joint,
    servo: Servo,
    taken: set[str],
    cap: EffortCap | None = None,
) -> ActuatorRecord:
    """The actuator of a choice, its gains worked out from the joint's effective inertia; a
    ``cap`` replaces a placeholder effort."""
    name = choice.joint if choice.joint not in taken else f"{choice.joint}_actuator"
    record = actuator_record(choice, name)
    if cap is not None:
        record.forcerange = [-cap.holding, cap.holding]
        record.placeholder_effort = cap.effort
    added = 0.0  # armature this servo adds to the joint
    line = _urdf_line(choice, record, cap, servo.timestep)
    if line is not None:
        record.motor = line.to_dict()
        # The drive's rotor, in every pose: the link's inertia at home says nothing of a folded
        # arm's. A rule's armature replaces it.
        if choice.armature is None:
            added = line.armature
            servo = replace(servo, inertia=servo.inertia + added)
    inertia = servo.inertia
    omega = servo.omega(choice.frequency, choice.stiffen)
    if choice.type == POSITION:
        record.kp = choice.kp or inertia * omega**2
        record.kv = choice.kv or 2 * choice.damping_ratio * inertia * omega
        # Weight-bearing: stiff enough to hold the pendulum the robot forms over its feet and
        # to bend at most SAG under its load at home (past the ceiling on omega, which the
        # damping below, for what the joint moves while standing, keeps stable).
        # A named drive (motors:) keeps the servo its datasheet sizes: its armature and
        # torque-speed line are the robot's, not a repair.
        if servo.carried > 0 and choice.stiffen and choice.kp is None and choice.motor is None:
            record.kp = max(record.kp, servo.pendulum * MARGIN, servo.load / servo.sag)
            # A stiff servo on a light foot rings faster than the time step can follow once
            # the foot leaves the floor: the rotor inertia a real drive has (armature) keeps
            # sqrt(kp / I) dt at STEP_RATIO.
            floor = record.kp * (servo.timestep / STEP_RATIO) ** 2
            if choice.armature is None and floor > inertia:
                added += floor - inertia
                inertia = floor
            if choice.kv is None:
                moved = inertia + servo.carried
                record.kv = 2 * choice.damping_ratio * math.sqrt(record.kp * moved)
            record.weight_bearing = True
        bounds = joint_range(joint)
        # A locked joint (lower = upper) has no range to command, and a placeholder range
        # (+-1e16) none worth commanding over.
        real = bounds is not None and bounds[0] < bounds[1] and not placeholder_range(bounds)
        record.ctrlrange = list(bounds) if real and bounds else None
    elif choice.type == VELOCITY:
        # A first-order servo with bandwidth omega, that reaches its command: the joint's own
        # damping b keeps b / (kv + b) of the speed from it (a wheel's 0.2 N m s against a kv
        # of 0.044 from its inertia reached 18 %).
        damping = choice.damping if choice.damping is not None else joint.damping
        record.kv = choice.kv or max(inertia * omega, VELOCITY_TRACKING * damping)
        velocity = positive_velocity(joint)
        record.ctrlrange = [-velocity, velocity] if velocity else None
    else:  # motor
        record.ctrlrange, record.forcerange = record.forcerange, None
    record.armature = added or None
    settle_kind(record, choice.runtime_commanded)  # issue 33, 42: a <dcmotor> or not
    return record


def runtime_line_notes(choices: list[ActuatorChoice]) -> list[str]:
    """One note naming the joints whose motor's torque-speed line is left out because
    ros2_control commands their position (they get <position> servos, issue 42)."""
    joints = [
        c.joint
        for c in choices
        if c.runtime_commanded and c.type == POSITION and has_speed_line(c.motor)
    ]
    if not joints:
        return []
    return [
        f"{len(joints)} ros2_control position joint{'s' if len(joints) > 1 else ''} "
        f"({', '.join(joints[:3])}{', ...' if len(joints) > 3 else ''}) get <position> servos "
        "without their motors' torque-speed lines: mujoco_ros2_control commands position only "
        "on an affine-bias servo (docs/ros2_control.md)"
    ]


def _urdf_line(
    choice: ActuatorChoice, record: ActuatorRecord, cap: EffortCap | None, timestep: float
):
    """The drive the URDF's effort and velocity limits make of a position servo that no motor
    names (None where a limit is missing or a placeholder replaced the effort)."""
    if choice.type != POSITION or choice.motor is not None or choice.speed_limit is None:
        return None
    if choice.runtime_commanded:  # it stays a <position> servo, which has no speed line
        return None
    if cap is not None or record.forcerange is None:
        return None
    effort = max(abs(value) for value in record.forcerange)
    return urdf_drive(effort, choice.speed_limit, timestep)


def _fill_user_records(readiness: Readiness, root) -> None:
    """Name the user's own actuators in their records."""
    section = root.find("actuator")
    if section is None:
        return
    by_joint = {
        (e.get("joint") or e.get("jointinparent")): e for e in section if e.tag in ACTUATOR_TAGS
    }
    # One on a fixed tendon drives the tendon's joints (the reference demo's gripper): the
    # report named it "" of type "user".
    tendons = {
        tendon.get("name"): [j.get("joint") for j in tendon.findall("joint")]
        for tendon in root.iter("fixed")
    }
    for element in section:
        if element.tag in ACTUATOR_TAGS and element.get("tendon"):
            for joint in tendons.get(element.get("tendon"), []):
                by_joint.setdefault(joint, element)
    for record in readiness.actuators:
        if record.source == USER and record.joint in by_joint:
            element = by_joint[record.joint]
            record.name = element.get("name") or ""
            record.type = element.tag


def _preset_ctrl(model, data, ctrl, preset: dict[str, float]) -> None:
    """An MJCF part's home ctrl for its actuators that drive no joint directly (joint
    actuators are set like the robot's own). A position servo on a tendon aims at the
    tendon's length at home, which robot.yaml's home may have changed; other actuators keep
    the part's home ctrl."""
    import mujoco

    direct = (mujoco.mjtTrn.mjTRN_JOINT, mujoco.mjtTrn.mjTRN_JOINTINPARENT)
    for name, value in preset.items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        if index < 0 or model.actuator_trntype[index] in direct:
            continue
        bias = model.actuator_biasprm[index]
        affine = model.actuator_biastype[index] == mujoco.mjtBias.mjBIAS_AFFINE
        ctrl[index] = float(data.actuator_length[index]) if affine and bias[1] != 0 else value
        if model.actuator_ctrllimited[index]:
            low, high = model.actuator_ctrlrange[index]
            ctrl[index] = min(max(ctrl[index], low), high)


def _integrates(model, actuator: int) -> bool:
    """Whether ``actuator`` integrates its ctrl into the position it aims at (an
    ``<intvelocity>``: an integrator into an affine position servo)."""
    import mujoco

    return bool(
        model.actuator_dyntype[actuator] == mujoco.mjtDyn.mjDYN_INTEGRATOR
        and model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE
        and model.actuator_biasprm[actuator][1] != 0
        and model.actuator_actadr[actuator] >= 0
    )


def _home_act(model, data):
    """Actuator states that hold the home pose: an ``<intvelocity>`` aims at it (its
    activation is the position), every other state rests at 0."""
    import mujoco
    import numpy as np

    act = np.zeros(model.na)
    for actuator in range(model.nu):
        if not _integrates(model, actuator):
            continue
        if model.actuator_trntype[actuator] != mujoco.mjtTrn.mjTRN_JOINT:
            continue
        joint = model.actuator_trnid[actuator, 0]
        gear = model.actuator_gear[actuator, 0] or 1.0
        value = gear * data.qpos[model.jnt_qposadr[joint]]
        if model.actuator_actlimited[actuator]:
            low, high = model.actuator_actrange[actuator]
            value = min(max(value, low), high)
        act[model.actuator_actadr[actuator] + model.actuator_actnum[actuator] - 1] = value
    return act


def _home_ctrl(model, data, torques):
    """Controls that hold the home pose: position servos aim at it, velocity servos rest, and
    motors push the ``torques`` that hold it (gravity, less the floor's support for a standing
    robot), all within their ctrlrange."""
    import mujoco
    import numpy as np

    ctrl = np.zeros(model.nu)
    for actuator in range(model.nu):
        if model.actuator_trntype[actuator] != mujoco.mjtTrn.mjTRN_JOINT:
            continue
        joint = model.actuator_trnid[actuator, 0]
        gear = model.actuator_gear[actuator, 0] or 1.0
        address, dof = model.jnt_qposadr[joint], model.jnt_dofadr[joint]
        bias = model.actuator_biasprm[actuator]
        affine = model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE
        if _integrates(model, actuator):  # an <intvelocity>: its ctrl is a speed, act the aim
            ctrl[actuator] = 0.0
        elif affine and bias[1] != 0:  # a position servo: force = kp (ctrl - length) ...
            ctrl[actuator] = gear * data.qpos[address]
        elif is_dcmotor(model, actuator):  # issue 33
            ctrl[actuator] = gear * data.qpos[address]  # a drive's position servo
        elif not affine and model.actuator_gaintype[actuator] == mujoco.mjtGain.mjGAIN_FIXED:
            ctrl[actuator] = torques[dof] / (gear * model.actuator_gainprm[actuator, 0])
        if model.actuator_ctrllimited[actuator]:
            low, high = model.actuator_ctrlrange[actuator]
            ctrl[actuator] = min(max(ctrl[actuator], low), high)
    return ctrl
