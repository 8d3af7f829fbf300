"""The model under mujoco_ros2_control's rules: what its hardware interface finds at start-up.

Read from the runtime's source (``mujoco_system_interface.cpp``, its 2026 releases) and
ros2_control's parser. For each ``<ros2_control>`` joint the runtime runs (a block written for
its plugin; every block where none is) with command interfaces, it finds the actuator on the
joint (else one named like the joint), classifies it by its bias
(:func:`~mjcfbuild.inputs.ros2_control.runtime_actuator_kind`) and:

- takes an interface that kind takes directly;
- takes position on a velocity, motor or custom actuator, and velocity on a motor or custom
  one, only through PID gains (``pid_gains.<interface>.<joint>`` of the ``pids_config_file``,
  read here as ROS reads it), and without them stops at start-up;
- logs an error for any other pairing (velocity on a position servo, effort on a servo) and
  goes on: the interface is still offered, and a controller that switches to it has its
  command written into the actuator's ctrl as it is (a velocity taken for a position);
- stops when a joint has no interface left.

A joint the URDF does not have stops ros2_control before the runtime ("not found in URDF");
a joint without an actuator, or a mimic joint, gets no command interface. For each sensor
with a ``mujoco_type`` it looks up MJCF sensors by name; cameras and lidars are matched by the
sensor's name. What stops the runtime, or leaves an interface or sensor the block names
unserved, is a failure here, naming the joint or sensor, the rule and the fix; what it logs
and survives is a warning, one line per kind. The block's transmissions are judged in
:mod:`~mjcfbuild.check.runtime_transmissions`, its ``mujoco_model`` in
:mod:`~mjcfbuild.check.runtime_model`.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from mjcfbuild.actuators import is_dcmotor
from mjcfbuild.check.runtime_actuators import (
    actuator_of,
    transmission_actuator,
    unnamed_joints,
    unsupported_transmissions,
)
from mjcfbuild.check.runtime_transmissions import unmatched_transmissions
from mjcfbuild.inputs.frames import ray_count, rays_short_of_max
from mjcfbuild.inputs.ros2_control import (
    BLOCK_CHILDREN,
    RUNTIME_PLUGINS,
    ControlJoint,
    Ros2Control,
    Transmission,
    expected_sensors,
    model_actuator_kind,
    needs_pids,
    takes_directly,
)

if TYPE_CHECKING:
    from mjcfbuild.inputs.pid_gains import PidGains

# The MJCF element of each sensor the runtime reads, as MuJoCo's sensor type names it.
_SENSOR_TYPES = {
    "framequat": "mjSENS_FRAMEQUAT",
    "framepos": "mjSENS_FRAMEPOS",
    "gyro": "mjSENS_GYRO",
    "accelerometer": "mjSENS_ACCELEROMETER",
    "force": "mjSENS_FORCE",
    "torque": "mjSENS_TORQUE",
    "magnetometer": "mjSENS_MAGNETOMETER",
}
_FIX = {
    "position": "a <position> servo (actuators.rules: type: position), or PID gains "
    "(a pids_config_file in <hardware>)",
    "velocity": "a <velocity> servo (actuators.rules: type: velocity), or PID gains "
    "(a pids_config_file in <hardware>)",
    "effort": "a <motor> (actuators.rules: type: motor)",
}
# The command interfaces the runtime knows; it skips others with a warning.
_KNOWN_INTERFACES = {"position", "velocity", "effort", "torque", "force"}
# qpos entries of each joint type (free, ball, slide, hinge), and the distance (m or rad)
# within which a start position counts as home's.
_QPOS_SIZE = {0: 7, 1: 4, 2: 1, 3: 1}
_SAME_POSITION = 1e-6
# The free joint the runtime publishes odometry from, unless odom_free_joint_name names one.
ODOM_FREE_JOINT = "floating_base_joint"


def check_runtime(
    model,
    control: Ros2Control,
    urdf_joints: dict[str, str | None],
    gains: PidGains | None = None,
    fixed_joints: frozenset[str] = frozenset(),
) -> tuple[dict, list[str], list[str]]:
    """The mapping mujoco_ros2_control makes of ``control`` on ``model`` (a JSON-friendly
    record), the failures (what stops it or leaves unserved) and warnings (what it logs).
    ``urdf_joints`` maps each URDF joint to the joint it mimics (None for others),
    ``fixed_joints`` names the URDF's fixed ones; ``gains`` are the pids_config_file's where
    it was read."""
    failures: list[str] = []
    warnings: list[str] = []
    ghosts, part_joints = _not_in_urdf(model, control, urdf_joints)
    failures += ghosts + _parser_refusals(control, urdf_joints, fixed_joints)
    failures += _unknown_children(control) + _refused_elements(control)
    warnings += part_joints + _interfaceless_joints(control)
    served = [
        joint
        for joint in control.joints
        if joint.commands
        and control.runs(joint.plugin)
        and (joint.name in urdf_joints or actuator_of(model, joint.name) >= 0)
        and joint.name not in fixed_joints
        and not _activated_mimic(joint, urdf_joints)
    ]
    mimics = [joint for joint in served if joint.mimic]
    warnings += _mimic_commands(mimics, urdf_joints)
    judged = [joint for joint in served if joint not in mimics]
    pids_file = control.hardware.get("pids_config_file")
    transmissions = [t for t in control.transmissions if t.in_ros2_control]
    joints = [
        _joint(model, joint, gains, bool(pids_file), failures, transmissions) for joint in judged
    ]
    sensors = [
        _sensor(model, sensor, failures)
        for sensor in control.sensors
        if sensor.params.get("mujoco_type") and control.runs(sensor.plugin)
    ]
    devices = [
        _device(model, sensor, failures, warnings)
        for sensor in control.sensors
        if sensor.kind and control.runs(sensor.plugin)
    ]
    failures += unnamed_joints(model) + unsupported_transmissions(model)
    failures += _unmatched_tendon_actuators(model)
    missing_failures, missing_warnings = _missing_keyframe(model, control)
    failures += missing_failures
    warnings += missing_warnings + _start_away_from_home(model, control, urdf_joints)
    odometry_failures, odometry_warnings = _odometry(model, control)
    failures += odometry_failures
    unmatched, transmission_warnings = unmatched_transmissions(
        model, control, urdf_joints, fixed_joints
    )
    failures += unmatched
    warnings += (
        _refusals(joints)
        + _effort_on_dcmotors(joints)
        + _effort_at_start(joints)
        + _unknown_pids(joints, control, gains)
        + odometry_warnings
        + _unread_sensors(control)
        + _other_blocks(control)
        + transmission_warnings
    )
    return {"joints": joints, "sensors": sensors, "devices": devices}, failures, warnings


def _not_in_urdf(
    model, control: Ros2Control, urdf_joints: dict[str, str | None]
) -> tuple[list[str], list[str]]:
    """ros2_control (Jazzy and later) refuses a description whose <ros2_control> names a
    joint its URDF lacks, in any block, before any hardware starts: a failure; a warning
    for a joint of an attached MJCF part (the model has it; the URDF handed to ros2_control
    must have it too)."""
    import mujoco

    from mjcfbuild.sources.packages import did_you_mean

    failures, warnings = [], []
    # A joint without a name attribute is refused for that (_refused_elements), not looked up.
    nameless = {r.origin for r in control.refusals if r.nameless == "joint"}
    for joint in control.joints:
        if joint.name in urdf_joints or joint.origin in nameless:
            continue
        if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint.name) >= 0:
            warnings.append(
                f"{joint.origin}: <ros2_control> joint '{joint.name}' is a joint of an "
                "attached MJCF part, not of the URDF: ros2_control (Jazzy and later) refuses a "
                "<ros2_control> joint its robot_description lacks, so give the controller "
                "manager a URDF that has it"
            )
            continue
        failures.append(
            f"{joint.origin}: <ros2_control> joint '{joint.name}' is not a joint of the "
            'URDF: ros2_control refuses the description at start-up ("... not found in '
            'URDF"); name a URDF joint, or use a <gpio> for what is no joint'
            f"{did_you_mean(joint.name, set(urdf_joints))}"
        )
    return failures, warnings


def _activated_mimic(joint: ControlJoint, urdf_joints: dict[str, str | None]) -> bool:
    """Whether ros2_control's parser takes ``joint`` for an activated mimic joint: it has a
    URDF <mimic> and its block does not say mimic="false"."""
    return bool(urdf_joints.get(joint.name)) and joint.mimic_attribute != "false"


def _parser_refusals(
    control: Ros2Control, urdf_joints: dict[str, str | None], fixed_joints: frozenset[str]
) -> list[str]:
    """What ros2_control's URDF parser (parse_control_resources_from_urdf, Jazzy and later)
    refuses before any hardware starts, in every block: a fixed joint; a mimic joint (a URDF
    <mimic>, unless mimic="false") with command interfaces, or whose leader is not in its
    block; mimic="true" on a joint the URDF gives no <mimic>."""
    failures = []
    for joint in control.joints:
        if joint.name not in urdf_joints:
            continue  # refused as a joint the URDF lacks
        refused = "ros2_control refuses the description at start-up"
        leader = urdf_joints.get(joint.name)
        if joint.name in fixed_joints:
            failures.append(
                f"{joint.origin}: <ros2_control> joint '{joint.name}' is a fixed joint: {refused} "
                '("Fixed joints do not make sense in ros2_control"); leave it out of the block'
            )
        elif joint.mimic_attribute == "true" and not leader:
            failures.append(
                f"{joint.origin}: <ros2_control> joint '{joint.name}' says mimic=\"true\" but "
                f'the URDF gives it no <mimic>: {refused} ("... has no mimic information in '
                'the URDF"); remove the attribute or add the <mimic>'
            )
        elif _activated_mimic(joint, urdf_joints):
            block = {other.name for other in control.joints if other.block == joint.block}
            if joint.commands:
                failures.append(
                    f"{joint.origin}: <ros2_control> joint '{joint.name}' mimics '{leader}' "
                    f'and has command interfaces: {refused} ("Activated mimic joints cannot '
                    'have command interfaces"); remove them (the joint follows its leader), or '
                    'say mimic="false" to command it on its own'
                )
            if leader not in block:
                failures.append(
                    f"{joint.origin}: <ros2_control> joint '{joint.name}' mimics '{leader}', "
                    f"which its block does not list: {refused} (\"Mimic joint '{leader}' not "
                    'found in <ros2_control> tag"); add the leader to the block'
                )
    return failures


def _unknown_children(control: Ros2Control) -> list[str]:
    """A child of a block ros2_control's parser does not know (parse_resource_from_xml: "invalid
    tag name ..."), in every block: it refuses the description before any hardware starts."""
    from mjcfbuild.sources.packages import did_you_mean

    return [
        f"{child.origin}: <ros2_control> holds a <{child.tag}> element, which ros2_control's "
        'parser does not know: it refuses the description at start-up ("invalid tag name '
        f'{child.tag}"); keep only {", ".join(f"<{tag}>" for tag in BLOCK_CHILDREN)} in the '
        f"block, and move the rest out of it{did_you_mean(child.tag, set(BLOCK_CHILDREN))}"
        for child in control.unknown_children
    ]


def _refused_elements(control: Ros2Control) -> list[str]:
    """Elements of any block that lack what ros2_control's parser reads of them (a name, a
    type, a <plugin>, an enable: inputs.ros2_control_parser): it stops the controller manager
    before any hardware starts."""
    return [
        f"{refusal.origin}: {refusal.what}: ros2_control's parser stops the runtime at "
        f'start-up ("{refusal.said}"); {refusal.fix}'
        if not refusal.said.startswith("the parser")
        else f"{refusal.origin}: {refusal.what}: {refusal.said} at start-up; {refusal.fix}"
        for refusal in control.refusals
    ]


def _interfaceless_joints(control: Ros2Control) -> list[str]:
    """Joints of the blocks the runtime runs with no command interface and no position,
    velocity or effort state interface: export_state_interfaces and export_command_interfaces
    export nothing else for a joint, so no controller or broadcaster finds it. (A joint whose
    command interfaces are all unknown is judged with its actuator.)"""
    names = [
        joint.name
        for joint in control.joints
        if control.runs(joint.plugin)
        and not joint.commands
        and joint.states is not None
        and not any(_family(state) in _KNOWN_INTERFACES for state in joint.states)
    ]
    if not names:
        return []
    first = next(joint for joint in control.joints if joint.name == names[0])
    them = "it" if len(names) == 1 else "them"
    return [
        f"{first.origin}: mujoco_ros2_control: {len(names)} <ros2_control> joint"
        f"{'s' if len(names) > 1 else ''} ({_first_few(names)}) "
        f"{_verb(names, 'has', 'have')} no position, velocity or effort interface, so the "
        f"runtime exports none for {them}: joint_state_broadcaster publishes no state of {them} "
        f'and no controller can claim {them}; add <state_interface name="position"/> (or leave '
        "the joint out of the block)"
    ]


def _mimic_commands(mimics: list[ControlJoint], urdf_joints: dict[str, str | None]) -> list[str]:
    """Joints a ``<param name="mimic">`` makes follow a leader: the runtime gives their
    command interfaces nothing to drive and logs an error."""
    if not mimics:
        return []
    named = _first_few([f"{joint.name} (mimics {joint.mimic})" for joint in mimics])
    return [
        f"mujoco_ros2_control: {len(mimics)} mimic joint{'s' if len(mimics) > 1 else ''} "
        f"({named}) {_verb(mimics, 'declares', 'declare')} command interfaces, which "
        "the runtime ignores (it logs an "
        "error): the joint follows its leader; command the leader, and remove the mimic "
        "joint's command interfaces"
    ]


def _odometry(model, control: Ros2Control) -> tuple[list[str], list[str]]:
    """The runtime publishes the floating base's odometry from the free joint named by
    ``odom_free_joint_name`` (default ``floating_base_joint``); a joint of that name that is
    not free stops it."""
    import mujoco

    if not any(control.runs(joint.plugin) for joint in control.joints):
        return [], []
    named = control.hardware.get("odom_free_joint_name")
    wanted = named or ODOM_FREE_JOINT
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, wanted)
    free = [
        model.joint(j).name
        for j in range(model.njnt)
        if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE and model.joint(j).name
    ]
    if index >= 0 and model.jnt_type[index] != mujoco.mjtJoint.mjJNT_FREE:
        return [
            f"{control.at('odom_free_joint_name')}<hardware> odom_free_joint_name names joint "
            f"'{wanted}', which is not a free "
            'joint: mujoco_ros2_control stops at start-up ("... since it is not a free '
            f'joint"); name the free joint{f" ({free[0]})" if free else ""}'
        ], []
    if index < 0 and free:
        where = (
            f"odom_free_joint_name names '{wanted}'"
            if named
            else (f"no odom_free_joint_name is given (it defaults to '{ODOM_FREE_JOINT}')")
        )
        return [], [
            f"{control.at('odom_free_joint_name')}mujoco_ros2_control: {where}, which the model "
            "does not have, so the runtime "
            f"publishes no odometry of the floating base; add <param "
            f'name="odom_free_joint_name">{free[0]}</param> to the <hardware>'
        ]
    return [], []


def _unread_sensors(control: Ros2Control) -> list[str]:
    """Sensors the runtime registers nothing for: no ``mujoco_type`` and no camera or lidar
    parameters (a broadcaster then finds none of their state interfaces)."""
    names = [
        sensor.name
        for sensor in control.sensors
        if control.runs(sensor.plugin) and not sensor.params.get("mujoco_type") and not sensor.kind
    ]
    if not names:
        return []
    shown = _first_few(names)
    return [
        f"mujoco_ros2_control: {len(names)} <ros2_control> sensor{'s' if len(names) > 1 else ''} "
        f"({shown}) {_verb(names, 'has', 'have')} no mujoco_type parameter, so the runtime "
        "serves none of their state "
        'interfaces; add <param name="mujoco_type">imu</param> (or fts, pose, magnetometer)'
    ]


def _other_blocks(control: Ros2Control) -> list[str]:
    """Blocks for other hardware beside one for mujoco_ros2_control: the runtime serves none
    of their joints."""
    lines = []
    for plugin in dict.fromkeys(control.plugins):
        if control.runs(plugin):
            continue
        names = [j.name for j in control.joints if j.plugin == plugin and j.commands]
        if not names:
            continue
        shown = _first_few(names)
        lines.append(
            f"mujoco_ros2_control: the <ros2_control> block for {plugin} is not the runtime's "
            f"(another block is written for {RUNTIME_PLUGINS}...), so it serves none of its "
            f"joints' command interfaces ({shown}); move them to that block to command them "
            "in simulation"
        )
    return lines


def _unmatched_tendon_actuators(model) -> list[str]:
    """The runtime registers every actuator of the model, a tendon's under the joint of its
    name; one named like no joint stops it ("Tendon actuator ... has no matching joint")."""
    import mujoco

    failures = []
    for index in range(model.nu):
        if model.actuator_trntype[index] != mujoco.mjtTrn.mjTRN_TENDON:
            continue
        name = model.actuator(index).name
        if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name) >= 0:
            continue
        tendon = model.tendon(model.actuator_trnid[index][0]).name
        failures.append(
            f"actuator '{name or f'#{index}'}' drives tendon '{tendon}' and no joint is named "
            'like it: mujoco_ros2_control stops at start-up ("Tendon actuator ... has no '
            'matching joint"); name the actuator after the joint it drives'
        )
    return failures


def _missing_keyframe(model, control: Ros2Control) -> tuple[list[str], list[str]]:
    """``initial_keyframe`` names a keyframe the runtime starts from; none of that name stops
    it: register_mujoco_actuators logs "Failed to apply initial keyframe: 'NAME'" and returns
    false, and on_init "Failed to register MuJoCo actuators, exiting..." (mujoco_ros2_control's
    mujoco_system_interface.cpp). It tries an override_start_position_file first and reads the
    keyframe only where that file fails to load: a warning then. The failures and the
    warnings."""
    keyframe = control.hardware.get("initial_keyframe")
    if not keyframe:
        return [], []
    names = [model.key(index).name for index in range(model.nkey)]
    if keyframe in names:
        return [], []
    listing = ", ".join(f"'{name}'" for name in names if name) or "none"
    logged = (
        f'("Failed to apply initial keyframe: \'{keyframe}\'", then "Failed to register MuJoCo '
        'actuators, exiting...")'
    )
    said = (
        f"{control.at('initial_keyframe')}<hardware> param initial_keyframe names keyframe "
        f"'{keyframe}', which the model does not have (its keyframes: {listing}): "
        f"mujoco_ros2_control stops at start-up {logged}"
    )
    if control.hardware.get("override_start_position_file"):
        return [], [
            said + " where the override_start_position_file, which it reads first, fails to "
            "load; name one of them, or leave the param out"
        ]
    return [said + "; name one of them"], []


def _start_away_from_home(
    model, control: Ros2Control, urdf_joints: dict[str, str | None]
) -> list[str]:
    """Without an ``initial_keyframe`` the runtime never applies the home keyframe: it starts
    each joint of its blocks that has a position state interface at its ``initial_value`` (0
    without one) and every other joint, a floating base included, where the MJCF puts it
    (qpos0). The check judges standing and holding from home, so a start elsewhere is said."""
    import mujoco

    # register_mujoco_actuators: an override_start_position_file, else the keyframe, is the start.
    if control.hardware.get("initial_keyframe") or control.hardware.get(
        "override_start_position_file"
    ):
        return []
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if home < 0:
        return []
    starts = {
        joint.name: joint.initial if joint.initial is not None else 0.0
        for joint in control.joints
        if control.runs(joint.plugin) and joint.position_state
    }
    away: list[str] = []
    base_away = False
    for index in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, index) or ""
        if urdf_joints.get(name):
            continue  # a mimic follower: its equality puts it where its leader is
        first = model.jnt_qposadr[index]
        size = _QPOS_SIZE[int(model.jnt_type[index])]
        at_home = model.key_qpos[home, first : first + size]
        start = model.qpos0[first : first + size].copy()
        if size == 1 and name in starts:
            start[0] = starts[name]
        if max(abs(start - at_home)) <= _SAME_POSITION:
            continue
        if size == 1:
            away.append(f"{name} at {start[0]:.3g} instead of {at_home[0]:.3g}")
        elif model.jnt_type[index] == mujoco.mjtJoint.mjJNT_FREE:
            base_away = True
        else:
            away.append(f"{name} where the MJCF puts it")
    if not away and not base_away:
        return []
    what = []
    if away:
        what.append(
            f"{len(away)} joint{'s' if len(away) > 1 else ''} away from the home keyframe "
            f"the check judges ({_first_few(away)})"
        )
    if base_away:
        what.append("the floating base where the MJCF puts it, not at home")
    return [
        "mujoco_ros2_control: <hardware> names no initial_keyframe, so the runtime starts "
        + " and ".join(what)
        + " (a joint with a position state interface starts at its initial_value, 0 without "
        'one; any other where the MJCF puts it); add <param name="initial_keyframe">home'
        "</param> to <hardware> to start where the check's stand and hold tests start"
    ]


def _effort_on_dcmotors(joints: list[dict]) -> list[str]:
    """One warning for joints whose effort command would reach a <dcmotor>: the runtime takes
    it for a custom actuator and writes the effort into its ctrl, which the <dcmotor> reads as
    a position target or a voltage, not a torque."""
    names = [
        j["joint"]
        for j in joints
        if j.get("dcmotor") and any(i in ("effort", "torque", "force") for i in j["interfaces"])
    ]
    if not names:
        return []
    return [
        f"mujoco_ros2_control: {len(names)} joint{'s' if len(names) > 1 else ''} "
        f"({', '.join(names[:3])}{', ...' if len(names) > 3 else ''}) command effort on a "
        "<dcmotor>, which reads its ctrl as a position target or a voltage, not a torque; give "
        "them a <motor> (actuators.rules: type: motor)"
    ]


def _refusals(joints: list[dict]) -> list[str]:
    """One warning per (interface, actuator kind) the runtime logs an error for and goes on:
    it still offers the interface, and a controller that switches to it has its command
    written into the actuator's ctrl as it is."""
    refused: dict[tuple[str, str], list[str]] = {}
    for joint in joints:
        for interface, way in joint["how"].items():
            if way is None:
                refused.setdefault((interface, joint["kind"]), []).append(joint["joint"])
    lines = []
    for (interface, kind), names in sorted(refused.items()):
        listed = _first_few(names)
        who = f"{len(names)} joint{'s' if len(names) > 1 else ''} ({listed})"
        if _family(interface) not in _KNOWN_INTERFACES:
            lines.append(
                f"mujoco_ros2_control: {who} {_verb(names, 'declares', 'declare')} "
                f"{_article(interface)} {interface} command interface, which the runtime does "
                "not know: it skips it with a warning; remove it"
            )
            continue
        lines.append(
            f"mujoco_ros2_control: {who} {_verb(names, 'declares', 'declare')} "
            f"{_article(interface)} {interface} command "
            f"interface that their {kind} actuators do not take: the runtime logs an error but "
            f"offers it, and a controller that switches to it has its {interface} command "
            f"written into the {kind} actuator's ctrl as it is; {_switch_fix(interface, kind)}"
        )
    return lines


def _first_few(names: list[str]) -> str:
    """The first three of ``names``, and how many more there are."""
    return ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")


def _verb(subjects: list, one: str, many: str) -> str:
    """The verb agreeing with a count of ``subjects``."""
    return one if len(subjects) == 1 else many


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiou" else "a"


def _switch_fix(interface: str, kind: str) -> str:
    """How a joint gets an interface its actuator refuses besides the ones it takes."""
    if kind in ("motor", "custom"):
        return "name PID gains for it in a pids_config_file, or remove the interface"
    return (
        "to switch between interfaces, drive the joint with a <motor> (actuators.rules: type: "
        "motor) and PID gains in a pids_config_file, or remove the interface"
    )


def _effort_at_start(joints: list[dict]) -> list[str]:
    """Joints the runtime starts under effort control: it writes their effort command (0
    until a controller sends one) into ctrl, in place of the home keyframe's torques."""
    names = [joint["joint"] for joint in joints if joint.get("starts") == "effort"]
    if not names:
        return []
    shown = _first_few(names)
    return [
        f"mujoco_ros2_control: {len(names)} joint{'s' if len(names) > 1 else ''} ({shown}) "
        f"{_verb(names, 'starts', 'start')} under effort control: the runtime writes the "
        "effort command, 0 until a controller sends one, into ctrl in place of the home "
        "keyframe's, so the robot holds home only once a controller does (the check's hold "
        "test keeps the keyframe's torques)"
    ]


def _unknown_pids(joints: list[dict], control: Ros2Control, gains: PidGains | None) -> list[str]:
    """A pids_config_file the check could not read: which interfaces it then cannot judge."""
    pids_file = control.hardware.get("pids_config_file")
    if not pids_file or gains is not None:
        return []
    names = [
        f"{joint['joint']} {interface}"
        for joint in joints
        for interface, way in joint["how"].items()
        if way == "pid?"
    ]
    if not names:
        return []
    shown = _first_few(names)
    return [
        f"{control.at('pids_config_file')}mujoco_ros2_control: the pids_config_file {pids_file} "
        "could not be read here, so "
        f"whether the runtime finds PID gains for {shown} is not checked (without them it "
        "stops at start-up); build where the file is, or give its package in robot.yaml"
    ]


def _family(interface: str) -> str:
    return "effort" if interface in ("torque", "force") else interface


def _joint(
    model,
    joint: ControlJoint,
    gains: PidGains | None,
    pids_file: bool,
    failures: list[str],
    transmissions: list[Transmission],
) -> dict:
    """What the runtime makes of one commanded joint: its actuator, the actuator's kind and
    how each interface is taken ('direct', 'pid', 'pid?' where the pids_config_file could not
    be read, 'no pid' where the gains are missing, None where refused with a logged error).
    A joint with no actuator of its own is driven by its block's transmission's, whose PID
    gains are read under the joint that actuator stands for."""
    import mujoco

    name, commands = joint.name, joint.commands
    actuator, gains_of = actuator_of(model, name), name
    through = next(
        (t.actuators for t in transmissions if t.block == joint.block and t.joint == name), []
    )
    if actuator < 0 and (found := transmission_actuator(model, through)):
        actuator, gains_of = found
    if actuator < 0:
        failures.append(
            f"{joint.origin}: mujoco_ros2_control: joint '{name}' commands "
            f"{', '.join(commands)} but has no actuator (the runtime looks for one on the "
            f"joint, then one named '{name}'): the runtime starts but offers none of its "
            "command interfaces, so no controller can claim them; drive it (actuators.rules) "
            "or remove its command interfaces"
        )
        return {"joint": name, "interfaces": commands, "actuator": None, "kind": None, "how": {}}
    kind = model_actuator_kind(model, actuator)
    label = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, actuator) or f"#{actuator}"
    how: dict[str, str | None] = {}
    for interface in commands:
        family = _family(interface)
        if takes_directly(kind, interface):
            how[interface] = "direct"
        elif needs_pids(kind, interface):
            if gains is not None:
                how[interface] = "pid" if gains.has(family, gains_of) else "no pid"
            else:
                how[interface] = "pid?" if pids_file else "no pid"
        else:
            how[interface] = None
    missing = [interface for interface, way in how.items() if way == "no pid"]
    if missing:
        why = [gains.faults.get((_family(i), gains_of)) if gains else None for i in missing]
        detail = "; ".join(
            f"pid_gains.{_family(i)}.{gains_of}: {fault}"
            for i, fault in zip(missing, why, strict=True)
            if fault
        )
        given = "the pids_config_file gives none" if gains else "no pids_config_file gives them"
        failures.append(
            f"{joint.origin}: mujoco_ros2_control: joint '{name}' commands "
            f"{' and '.join(missing)} on its {kind} actuator '{label}', which the runtime "
            f"takes only through PID gains, and {given}"
            f'{f" ({detail})" if detail else ""}: it stops at start-up ("... not supported '
            f'with motor or custom actuator without defining the PIDs"); give '
            f"pid_gains.{_family(missing[0])}.{gains_of}.p, .i and .d as doubles in a "
            f"pids_config_file, or {_FIX.get(_family(missing[0]), '').split(', or')[0]}"
        )
    elif not any(how.values()):
        known = [i for i in commands if _family(i) in _FIX]
        fix = (
            f"give it {_FIX[_family(known[0])]}"
            if known
            else "declare position, velocity or effort, which the runtime knows"
        )
        failures.append(
            f"{joint.origin}: mujoco_ros2_control: joint '{name}' commands "
            f"{', '.join(commands)}, none of which its actuator '{label}' ({kind}, as the "
            'runtime classifies it) takes, so the runtime stops at start-up ("... none are '
            f'supported by its MuJoCo actuator(s)"); {fix}'
        )
    return {
        "joint": name,
        "interfaces": commands,
        "actuator": label,
        "kind": kind,
        "how": how,
        "dcmotor": is_dcmotor(model, actuator),
        "starts": _starting_mode(kind, how),
    }


def _starting_mode(kind: str, how: dict[str, str | None]) -> str | None:
    """The control mode the runtime starts a joint in: a position or velocity servo in its
    own; a motor or custom actuator in position or velocity through PIDs where the joint has
    them (in that order), else effort; None where it does not start (PIDs missing)."""
    if "no pid" in how.values():
        return None
    if kind in ("position", "velocity"):
        return kind
    for interface in ("position", "velocity"):
        if how.get(interface) in ("pid", "pid?"):
            return interface
    return "effort"


def _sensor(model, sensor, failures: list[str]) -> dict:
    import mujoco

    found = []
    for expected in expected_sensors(sensor):
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, expected.name)
        entry = {"name": expected.name, "type": expected.tag, "found": index >= 0, "site": None}
        where = f"mujoco_ros2_control: sensor '{sensor.name}' ({sensor.params['mujoco_type']})"
        if index < 0:
            failures.append(
                f"{where} reads the MJCF {expected.tag} '{expected.name}', which the model "
                "does not have; add it (mujoco_inputs raw) or let the build write it"
            )
        else:
            wanted = getattr(mujoco.mjtSensor, _SENSOR_TYPES[expected.tag])
            if model.sensor_type[index] != wanted:
                failures.append(
                    f"{where}: MJCF sensor '{expected.name}' is not a {expected.tag}; the "
                    f"runtime reads its {expected.measures} from one"
                )
            if model.sensor_objtype[index] == mujoco.mjtObj.mjOBJ_SITE:
                entry["site"] = mujoco.mj_id2name(
                    model, mujoco.mjtObj.mjOBJ_SITE, int(model.sensor_objid[index])
                )
        found.append(entry)
    return {"sensor": sensor.name, "type": sensor.params["mujoco_type"], "mjcf": found}


def _device(model, sensor, failures: list[str], warnings: list[str]) -> dict:
    """A camera (by name) or lidar (rangefinders named after it, one per ray)."""
    import mujoco

    if sensor.kind == "camera":
        camera = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, sensor.name)
        if camera < 0:
            failures.append(
                f"mujoco_ros2_control: camera sensor '{sensor.name}' has no MuJoCo camera of "
                "its name; add one (mujoco_inputs cameras)"
            )
        elif list(model.cam_resolution[camera]) == [1, 1]:
            warnings.append(
                f"{sensor.origin}: camera '{sensor.name}' has no resolution, so "
                "mujoco_ros2_control renders it at MuJoCo's default of 1 x 1 pixels; give "
                "its input a resolution (mujoco_inputs cameras: resolution: [640, 480])"
            )
        return {"sensor": sensor.name, "kind": "camera", "found": camera >= 0}
    pattern = re.compile(rf"{re.escape(sensor.name)}(-\d+)?")
    rays = sum(
        1
        for index in range(model.nsensor)
        if model.sensor_type[index] == mujoco.mjtSensor.mjSENS_RANGEFINDER
        and pattern.fullmatch(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SENSOR, index) or "")
    )
    expected = _rays(sensor.params)
    if rays == 0:
        failures.append(
            f"mujoco_ros2_control: lidar sensor '{sensor.name}' has no MuJoCo rangefinder of "
            "its name; add one (mujoco_inputs lidars)"
        )
    elif expected is not None and rays != expected:
        failures.append(
            f"mujoco_ros2_control: lidar sensor '{sensor.name}' has {rays} rangefinders, but "
            f"its angles give {expected} rays; make the lidar input's angles match"
        )
    if expected is not None and _short_of_max(sensor.params):
        warnings.append(
            f"{sensor.origin}: lidar sensor '{sensor.name}': (max_angle - min_angle) / "
            f"angle_increment falls just short of a whole number in floating point, so "
            f"mujoco_ros2_control scans {expected} rays and none at max_angle, which its scan "
            "message still states; raise max_angle by a hair (1e-7) to scan there too"
        )
    return {
        "sensor": sensor.name,
        "kind": "lidar",
        "found": rays > 0,
        "rays": rays,
        "expected_rays": expected,
    }


def _rays(params: dict[str, str]) -> int | None:
    try:
        low, high = float(params["min_angle"]), float(params["max_angle"])
        step = float(params["angle_increment"])
    except (KeyError, ValueError):
        return None
    return ray_count(low, high, step) if step > 0 and high >= low else None


def _short_of_max(params: dict[str, str]) -> bool:
    """Whether the runtime's ray count leaves out the ray at max_angle the angles mean."""
    low, high = float(params["min_angle"]), float(params["max_angle"])
    return rays_short_of_max(low, high, float(params["angle_increment"]))
