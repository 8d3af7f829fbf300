"""The tuning report: how each group of generated servos actually responds in the built model.

Actuators are grouped by the ``actuators.rules`` entry that made them (else by type: the default
position servos, the default velocity servos). For each group the built model is simulated from
home, in a copy where

- contacts are off (each servo is measured on its own, not against the floor or the robot's own
  body), and
- a floating base is held where home puts it (its free joint removed): a leg's servo is measured
  as on a test stand, not through the robot's balance;

gravity stays on. The robot first holds its home ``ctrl`` for :data:`SETTLE` s; then every
actuator of the group is commanded, at once, a step of :data:`STEP` (rad, m, or rad/s for a
velocity servo) away from home (towards the wider side of its range), for :data:`WINDOW` s; and,
from the same settled state, a sine of that amplitude at :data:`SINE_HZ` Hz for
:data:`WINDOW` s. The other actuators hold home. Per joint, from the step:

- rise time: from 10 % to 90 % of the way from the settled value to the final value (the mean
  of the last 10 % of the window);
- overshoot: how far past the final value the joint went, in % of the step it made;
- settling time: from the step until the joint stays within 2 % of the step of its final value;
- steady-state error: final value against the command (what gravity leaves, torque / kp);

and from the sine the largest tracking error; over both, saturation: the share of time the
actuator's force was at its limit (its force range: a drive's peak torque; and, in the direction
of motion, a drive's torque-speed line). A group's row shows its worst
joint for each figure. Crossing times are interpolated between steps.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import asdict, dataclass, field

from mjcfbuild.actuators import DCMOTOR, POSITION_KINDS, VELOCITY

SETTLE = 0.5  # s of holding home before each test
WINDOW = 1.5  # s of each test
STEP = 0.1  # rad (m for a slide, rad/s for a velocity servo)
SINE_HZ = 1.0
SETTLED = 0.02  # the settling band, a share of the step
SATURATED = 0.999  # a force at this share of its limit counts as saturated
TUNED_TYPES = (*POSITION_KINDS, VELOCITY)


@dataclass
class JointResponse:
    """One joint's figures (seconds, a share, rad or m)."""

    joint: str
    step: float  # the commanded step (signed)
    rise_time: float | None
    overshoot: float
    settling_time: float | None  # None: not settled within the window
    steady_state_error: float
    tracking_error: float
    saturation: float


@dataclass
class GroupResponse:
    """A group of actuators, its joints' figures and the traces its plot draws."""

    name: str
    label: str
    kind: str  # position or velocity
    joints: list[JointResponse] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    step_traces: dict[str, list[float]] = field(default_factory=dict)  # share of the step
    sine_traces: dict[str, list[float]] = field(default_factory=dict)  # share of the amplitude
    sine_reference: list[float] = field(default_factory=list)

    def summary(self) -> dict:
        """The group's worst figures, for the report's table."""
        rises = [j.rise_time for j in self.joints if j.rise_time is not None]
        settles = [j.settling_time for j in self.joints]
        return {
            "group": self.name,
            "label": self.label,
            "kind": self.kind,
            "joints": [j.joint for j in self.joints],
            "rise_time": max(rises) if rises else None,
            "overshoot": max(j.overshoot for j in self.joints),
            "settling_time": None if None in settles else max(settles),  # type: ignore[type-var]
            "steady_state_error": max(j.steady_state_error for j in self.joints),
            "tracking_error": max(j.tracking_error for j in self.joints),
            "saturation": max(j.saturation for j in self.joints),
            "per_joint": [asdict(j) for j in self.joints],
        }


def groups_of(actuators: list[dict], rules: list[dict]) -> dict[str, tuple[str, list[dict]]]:
    """Group name -> (its label, its actuator records): records of the assembly's readiness
    (generated servos only), grouped by rule, else by type."""
    groups: dict[str, tuple[str, list[dict]]] = {}
    for record in actuators:
        if record.get("type") not in TUNED_TYPES or record.get("source") in ("user", "part"):
            continue
        rule = record.get("rule")
        if rule is not None and rule < len(rules):
            name = f"rule{rule}"
            label = f"actuators.rules[{rule}]: {', '.join(rules[rule].get('joints', []))}"
        else:
            kind = "velocity" if record["type"] == "velocity" else "position"
            name, label = f"default_{kind}", f"default {kind} servos"
        groups.setdefault(name, (label, []))[1].append(record)
    return dict(sorted(groups.items()))


def stand_spec(spec) -> None:
    """Make ``spec`` (a copy of the built model) the test stand: contacts and sensors off
    (nothing reads them; a lidar's rays cost most of a step), every free joint removed (its
    body held where it is), keyframes dropped."""
    import mujoco

    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_SENSOR
    for joint in list(spec.joints):
        if joint.type == mujoco.mjtJoint.mjJNT_FREE:
            spec.delete(joint)
    for key in list(spec.keys):
        spec.delete(key)


def measure(model, home_qpos: dict[str, float], home_ctrl: dict[str, float], groups) -> list:
    """Simulate every group on ``model`` (a test stand); ``home_qpos`` and ``home_ctrl``: the
    home keyframe by joint and by actuator name."""
    import mujoco
    import numpy as np

    data = mujoco.MjData(model)
    for joint, value in home_qpos.items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
        if index >= 0:
            data.qpos[model.jnt_qposadr[index]] = value
    ctrl = np.zeros(model.nu)
    for name, value in home_ctrl.items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        if index >= 0:
            ctrl[index] = value
    data.ctrl[:] = ctrl
    mujoco.mj_forward(model, data)
    for _ in range(round(SETTLE / model.opt.timestep)):
        mujoco.mj_step(model, data)
    settled = mujoco.MjData(model)
    mujoco.mj_copyData(settled, model, data)
    results = []
    for name, (label, records) in groups.items():
        results.append(_group(model, settled, ctrl, name, label, records))
    return results


def _group(model, settled, ctrl, name: str, label: str, records: list[dict]) -> GroupResponse:
    import mujoco
    import numpy as np

    velocity = records[0]["type"] == "velocity"
    group = GroupResponse(name, label, "velocity" if velocity else "position")
    actuators, dofs, addresses, steps, limits, lines = [], [], [], [], [], []
    for record in records:
        actuator = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, record["name"])
        joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, record["joint"])
        if actuator < 0 or joint < 0:
            continue
        actuators.append(actuator)
        dofs.append(int(model.jnt_dofadr[joint]))
        addresses.append(int(model.jnt_qposadr[joint]))
        steps.append(_step_size(model, actuator, ctrl[actuator], velocity))
        forcerange = model.actuator_forcerange[actuator]
        limited = bool(model.actuator_forcelimited[actuator])
        limits.append(float(max(abs(forcerange[0]), abs(forcerange[1]))) if limited else math.inf)
        motor = record.get("motor") or {}
        speed_line = motor.get("no_load_speed") and record["type"] == DCMOTOR
        # A drive's torque-speed line: stall torque and no-load speed (inf: none).
        lines.append(
            (float(motor["stall_torque"]), float(motor["no_load_speed"]))
            if speed_line
            else (math.inf, math.inf)
        )
    count = round(WINDOW / model.opt.timestep)
    times = [(i + 1) * model.opt.timestep for i in range(count)]
    index = np.array(actuators, dtype=int)
    watched = np.array(dofs if velocity else addresses, dtype=int)
    step_array = np.array(steps)
    bounds = np.array(limits)
    stall = np.array([line[0] for line in lines])
    no_load = np.array([line[1] for line in lines])
    dof_index = np.array(dofs, dtype=int)

    def run(command):
        data = mujoco.MjData(model)
        mujoco.mj_copyData(data, model, settled)
        start = (data.qvel if velocity else data.qpos)[watched].copy()
        trace = np.zeros((count, len(index)))
        saturated = np.zeros(len(index))
        for i in range(count):
            data.ctrl[:] = ctrl
            data.ctrl[index] = ctrl[index] + command(i)
            speed = data.qvel[dof_index].copy()  # the speed the step's forces are computed at
            mujoco.mj_step(model, data)
            trace[i] = (data.qvel if velocity else data.qpos)[watched]
            force = data.actuator_force[index]
            # The limit: the force range, and in the direction of motion the torque-speed line.
            with np.errstate(invalid="ignore"):
                line = np.where(
                    force * speed > 0, stall * np.maximum(0.0, 1 - np.abs(speed) / no_load), np.inf
                )
            saturated += np.abs(force) >= SATURATED * np.minimum(bounds, line)
        return start, trace, saturated / count

    start, step_trace, step_saturation = run(lambda i: step_array)
    sine = [math.sin(2 * math.pi * SINE_HZ * t) for t in times]
    sine_start, sine_trace, sine_saturation = run(lambda i: step_array * sine[i])
    group.times = [round(t, 6) for t in times]
    for k, record in enumerate(r for r in records if _known(model, r)):
        values = step_trace[:, k]
        figures = step_figures(times, float(start[k]), values.tolist(), float(steps[k]))
        target = float(ctrl[index[k]] + steps[k])
        reference = ctrl[index[k]] + steps[k] * np.array(sine)
        offset = float(start[k]) - float(ctrl[index[k]])  # what gravity leaves at home
        tracking = float(np.max(np.abs(sine_trace[:, k] - offset - reference)))
        group.joints.append(
            JointResponse(
                joint=record["joint"],
                step=float(steps[k]),
                rise_time=figures["rise_time"],
                overshoot=figures["overshoot"],
                settling_time=figures["settling_time"],
                steady_state_error=abs(figures["final"] - target),
                tracking_error=tracking,
                saturation=float(max(step_saturation[k], sine_saturation[k])),
            )
        )
        made = figures["final"] - float(start[k])
        group.step_traces[record["joint"]] = [
            float(v - start[k]) / made if made else 0.0 for v in values
        ]
        group.sine_traces[record["joint"]] = [
            float(v - sine_start[k]) / steps[k] for v in sine_trace[:, k]
        ]
    group.sine_reference = list(sine)
    return group


def _known(model, record: dict) -> bool:
    import mujoco

    return (
        mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, record["name"]) >= 0
        and mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, record["joint"]) >= 0
    )


def _step_size(model, actuator: int, home: float, velocity: bool) -> float:
    """:data:`STEP` towards the wider side of the actuator's ctrlrange from home, and no
    further than that range allows."""
    if not model.actuator_ctrllimited[actuator]:
        return STEP
    low, high = (float(v) for v in model.actuator_ctrlrange[actuator])
    up, down = high - home, home - low
    size = min(STEP, max(up, down))
    return size if up >= down else -size


def step_figures(times: list[float], start: float, values: list[float], step: float) -> dict:
    """Rise time, overshoot (a share of the step made), settling time and final value of a
    step response sampled at ``times`` (from the step on) starting at ``start``."""
    tail = values[-max(1, len(values) // 10) :]
    final = sum(tail) / len(tail)
    made = final - start
    if made == 0 or step == 0:
        return {"rise_time": None, "overshoot": 0.0, "settling_time": None, "final": final}
    shares = [(v - start) / made for v in values]
    samples = [(0.0, 0.0), *zip(times, shares, strict=True)]
    low, high = _crossing(samples, 0.1), _crossing(samples, 0.9)
    rise = high - low if low is not None and high is not None else None
    overshoot = max(0.0, max(shares) - 1.0)
    band = SETTLED * abs(step / made)
    settling = 0.0
    for t, share in samples:
        if abs(share - 1.0) > band:
            settling = t
    settled = settling < times[-1] - 0.1 * WINDOW
    return {
        "rise_time": rise,
        "overshoot": overshoot,
        "settling_time": settling if settled else None,
        "final": final,
    }


def _crossing(samples: list[tuple[float, float]], level: float) -> float | None:
    """When the samples first reach ``level``, interpolated between the two around it."""
    for (t0, y0), (t1, y1) in itertools.pairwise(samples):
        if y0 < level <= y1:
            return t0 + (t1 - t0) * (level - y0) / (y1 - y0)
    return None
