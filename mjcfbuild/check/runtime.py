"""The model under mujoco_ros2_control's rules: what its hardware interface finds at start-up.

For each ``<ros2_control>`` joint with command interfaces, the runtime finds the actuator on
the joint (else one named like the joint), classifies it by its bias alone (motor, position,
velocity or custom: :func:`~mjcfbuild.inputs.ros2_control.runtime_actuator_kind`) and refuses
a command interface that kind does not take (without PID gains): it logs an error for each
such interface and refuses to start when a joint has no interface left. For each sensor with a
``mujoco_type`` it looks up MJCF sensors by name; cameras and lidars are matched by the
sensor's name. What stops the runtime or leaves a sensor unread is a failure here, naming the
joint or sensor, the rule and the fix; an interface refused beside one that works (the
runtime starts, but a controller cannot switch to it) is a warning, one line per kind.
"""

from __future__ import annotations

import re

from mjcfbuild.actuators import is_dcmotor
from mjcfbuild.inputs.frames import ray_count
from mjcfbuild.inputs.ros2_control import (
    Ros2Control,
    expected_sensors,
    interface_support,
    runtime_actuator_kind,
)

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


def check_runtime(model, control: Ros2Control) -> tuple[dict, list[str], list[str]]:
    """The mapping mujoco_ros2_control makes of ``control`` on ``model`` (a JSON-friendly
    record), the failures (what stops it or it cannot find) and warnings (interfaces it
    refuses beside ones it takes)."""
    failures: list[str] = []
    joints = [
        _joint(model, joint.name, joint.commands, joint.pids, failures)
        for joint in control.joints
        if joint.commands
    ]
    sensors = [
        _sensor(model, sensor, failures)
        for sensor in control.sensors
        if sensor.params.get("mujoco_type")
    ]
    devices = [_device(model, sensor, failures) for sensor in control.sensors if sensor.kind]
    failures += _unmatched_tendon_actuators(model)
    failures += _missing_keyframe(model, control.hardware.get("initial_keyframe"))
    unmatched, elsewhere = _unmatched_transmissions(model, control)
    failures += unmatched
    warnings = _refusals(joints) + _effort_on_dcmotors(joints) + elsewhere
    return {"joints": joints, "sensors": sensors, "devices": devices}, failures, warnings


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


def _missing_keyframe(model, keyframe: str | None) -> list[str]:
    """``initial_keyframe`` names a keyframe the runtime starts from; none of that name stops
    it ("Failed to find keyframe")."""
    if not keyframe:
        return []
    names = [model.key(index).name for index in range(model.nkey)]
    if keyframe in names:
        return []
    listing = ", ".join(f"'{name}'" for name in names if name) or "none"
    return [
        f"<hardware> param initial_keyframe names keyframe '{keyframe}', which the model does "
        f"not have (its keyframes: {listing}): mujoco_ros2_control stops at start-up "
        '("Failed to find keyframe"); name one of them'
    ]


# The hardware plugins of mujoco_ros2_control (MujocoSystemInterface, and older names) share
# its package's prefix: a <ros2_control> block naming another (a real robot's driver) is not
# run by it as written.
RUNTIME_PLUGINS = "mujoco_ros2_control/"


def _unmatched_transmissions(model, control: Ros2Control) -> tuple[list[str], list[str]]:
    """A ``<ros2_control>`` transmission's actuators are looked up as joints, then as
    actuators of the model; one that is neither stops the runtime ("Transmission actuator
    ... not found"): a failure in a block written for mujoco_ros2_control (or naming no
    plugin), one warning per other block (a real robot's driver: the runtime would stop only
    once the plugin is swapped for its own). The failures and the warnings."""
    import mujoco

    failures: list[str] = []
    elsewhere: dict[str, list[str]] = {}  # plugin -> its transmissions' missing actuators
    for transmission in control.transmissions:
        if not transmission.in_ros2_control:
            continue
        for name in transmission.actuators:
            if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name) >= 0:
                continue
            if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, name) >= 0:
                continue
            if transmission.plugin and not transmission.plugin.startswith(RUNTIME_PLUGINS):
                elsewhere.setdefault(transmission.plugin, []).append(name)
                continue
            failures.append(
                f"transmission {transmission.element} of joint '{transmission.joint}' names "
                f"actuator '{name}', which is neither a joint nor an actuator of the model: "
                'mujoco_ros2_control stops at start-up ("Transmission actuator ... not '
                'found"); name the joint or its actuator'
            )
    warnings = []
    for plugin, names in elsewhere.items():
        names = list(dict.fromkeys(names))
        shown = ", ".join(f"'{name}'" for name in names[:3])
        more = f" and {len(names) - 3} more" if len(names) > 3 else ""
        warnings.append(
            f"<ros2_control> transmissions for the hardware plugin {plugin} name actuators "
            f"the model lacks ({shown}{more}): run under mujoco_ros2_control, with its "
            "plugin, they would stop it at start-up; name the joints (or their actuators) there"
        )
    return list(dict.fromkeys(failures)), warnings


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
    """One warning per (interface, actuator kind) that the runtime refuses on joints where
    another of their interfaces works."""
    refused: dict[tuple[str, str], list[str]] = {}
    for joint in joints:
        usable = any(joint["how"].values())
        for interface, way in joint["how"].items():
            if usable and way is None:
                refused.setdefault((interface, joint["kind"]), []).append(joint["joint"])
    lines = []
    for (interface, kind), names in sorted(refused.items()):
        listed = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
        lines.append(
            f"mujoco_ros2_control: {len(names)} joint{'s' if len(names) > 1 else ''} "
            f"({listed}) declare a {interface} command interface that their {kind} actuators "
            f"do not take: the runtime logs an error for it and no controller can switch to "
            f"it; {_switch_fix(interface, kind)}"
        )
    return lines


def _switch_fix(interface: str, kind: str) -> str:
    """How a joint gets an interface its actuator refuses besides the ones it takes."""
    if kind in ("motor", "custom"):
        return "name PID gains for it in a pids_config_file, or remove the interface"
    return (
        "to switch between interfaces, drive the joint with a <motor> (actuators.rules: type: "
        "motor) and PID gains in a pids_config_file, or remove the interface"
    )


def _family(interface: str) -> str:
    return "effort" if interface in ("torque", "force") else interface


def actuator_of(model, joint: str) -> int:
    """The actuator the runtime finds for ``joint``: one on the joint, else one of its name
    (a tendon's, say); -1 where there is none."""
    import mujoco

    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
    if index >= 0:
        for actuator in range(model.nu):
            trn = model.actuator_trntype[actuator]
            if trn == mujoco.mjtTrn.mjTRN_JOINT and model.actuator_trnid[actuator, 0] == index:
                return actuator
    return mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, joint)


def _joint(model, name: str, commands: list[str], pids: bool, failures: list[str]) -> dict:
    import mujoco

    actuator = actuator_of(model, name)
    if actuator < 0:
        failures.append(
            f"mujoco_ros2_control: joint '{name}' commands {', '.join(commands)} but has no "
            f"actuator (the runtime looks for one on the joint, then one named '{name}'); "
            "drive it (actuators.rules) or remove its command interfaces"
        )
        return {"joint": name, "interfaces": commands, "actuator": None, "kind": None, "how": {}}
    kind = runtime_actuator_kind(
        int(model.actuator_biastype[actuator]),
        tuple(float(v) for v in model.actuator_biasprm[actuator]),
    )
    label = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, actuator) or f"#{actuator}"
    how = {interface: interface_support(kind, interface, pids) for interface in commands}
    if not any(how.values()):
        first = commands[0]
        failures.append(
            f"mujoco_ros2_control: joint '{name}' commands {', '.join(commands)}, none of which "
            f"its actuator '{label}' ({kind}, by its bias) takes, so the runtime refuses to "
            f"start; give it {_FIX.get(_family(first), '')}"
        )
    return {
        "joint": name,
        "interfaces": commands,
        "actuator": label,
        "kind": kind,
        "how": how,
        "dcmotor": is_dcmotor(model, actuator),
    }


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


def _device(model, sensor, failures: list[str]) -> dict:
    """A camera (by name) or lidar (rangefinders named after it, one per ray)."""
    import mujoco

    if sensor.kind == "camera":
        present = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, sensor.name) >= 0
        if not present:
            failures.append(
                f"mujoco_ros2_control: camera sensor '{sensor.name}' has no MuJoCo camera of "
                "its name; add one (mujoco_inputs cameras)"
            )
        return {"sensor": sensor.name, "kind": "camera", "found": present}
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
