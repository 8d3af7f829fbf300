"""Standing at home: what holding home's ctrl does to a floating robot, simulated.

The build tries it to decide whether a robot with no described pose needs a crouch
(:mod:`mjcfbuild.control.stand_up`); the check runs it for its stand verdict
(:mod:`mjcfbuild.check.control`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

STAND_SECONDS = 5.0
# Standing: the base may tilt this much (rad) and sink this share of its height at home.
STAND_TILT = 0.2
STAND_SINK = 0.1
# A centre of mass this far (m) inside the feet's edge makes a pose one to stand in: a robot
# that falls from it falls for its servos, not its pose.
POSE_MARGIN = 0.02
# A robot on wheels held by velocity servos may roll this far (m) while standing at home.
ROLL_TOLERANCE = 0.05


@dataclass
class StandTest:
    """What holding home's ctrl for 5 s from home did to a floating robot."""

    seconds: float
    max_tilt: float  # rad, the base's largest tilt from upright
    max_sink: float  # m, how far the base sank below its height at home at most
    home_height: float  # m, the base's height at home
    max_deviation: float  # of a watched joint from home
    joint: str | None  # the joint of max_deviation
    needs_controller: str  # why the robot cannot stand without a controller ('' if it can)
    com_margin: float = 0.0  # m, from the centre of mass to the edge of the feet's area at home
    # Wheels on velocity servos are judged by what a wheel should do - not let the robot roll
    # away - rather than by their angle, which is theirs to change.
    wheels: list[str] = field(default_factory=list)
    max_roll: float = 0.0  # m, how far the base moved along the floor at most
    wheel_kv: float = 0.0  # the smallest kv among the wheels' velocity servos

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return dict(self.__dict__)

    def fails(self, hold_tolerance: float) -> bool:
        """Whether the robot fell, sank or bent past the tolerances."""
        sink = STAND_SINK * max(self.home_height, 0.0) + 0.01
        return (
            self.max_tilt > STAND_TILT
            or self.max_sink > sink
            or self.max_deviation > hold_tolerance
            or self.rolled()
        )

    def rolled(self) -> bool:
        """Whether wheels on velocity servos let the robot roll away."""
        return bool(self.wheels) and self.max_roll > ROLL_TOLERANCE

    def failure(self, hold_tolerance: float, advice: str) -> str:
        """The check's failure line."""
        if self.max_tilt > STAND_TILT or self.max_sink > STAND_SINK * self.home_height + 0.01:
            fell = (
                f"the robot does not stand at home: holding home's ctrl for "
                f"{self.seconds:g} s its base tilted {self.max_tilt:.2g} rad and sank "
                f"{self.max_sink * 1000:.0f} mm (of {self.home_height * 1000:.0f} mm), its "
                f"centre of mass {self.com_margin * 1000:.0f} mm inside the edge of the area "
                "its feet span; "
            )
            if self.com_margin >= POSE_MARGIN:  # the pose is fine: the servos let it go
                return fell + (
                    "its servos do not hold it there: stiffen the joints that carry it (kp or "
                    "armature in an actuators rule), or lower option timestep"
                )
            return fell + (
                "give home: a pose it stands in (feet under the centre of mass, knees bent), "
                "or name an SRDF group_state with self_collision.srdf and home_state"
            )
        if self.rolled():
            return (
                f"the robot rolled {self.max_roll * 1000:.0f} mm standing at home for "
                f"{self.seconds:g} s (tolerance {ROLL_TOLERANCE * 1000:.0f} mm): the velocity "
                f"servos of its wheels ({', '.join(self.wheels)}, kv {self.wheel_kv:.3g}) do "
                "not hold it still; a velocity servo creeps at its load over kv, so raise "
                f"their kv about {self.max_roll / ROLL_TOLERANCE:.2g} times with a rule "
                f"(actuators: {{rules: [{{joints: [{', '.join(self.wheels)}], kv: "
                f"{round_up(self.wheel_kv * self.max_roll / ROLL_TOLERANCE)}}}]}})"
            )
        return (
            f"standing at home for {self.seconds:g} s, joint '{self.joint}' moved "
            f"{self.max_deviation:.3g} from home (check.hold_tolerance {hold_tolerance:g}); "
            + advice
        )


def stand_test(model, key: int, passive: set[str], seconds: float = STAND_SECONDS) -> StandTest:
    """Hold keyframe ``key``'s ctrl for ``seconds`` from it and watch the floating base."""
    import mujoco
    import numpy as np

    from mjcfbuild.control.standing import rolling_bodies, stance

    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, key)
    mujoco.mj_forward(model, data)
    rolling = rolling_bodies(model, data)
    found = stance(model, data, rolling)
    root = free_body(model)
    height = float(data.xpos[root][2]) - floor_height(model)
    if not found.can_stand:
        return StandTest(0.0, 0.0, 0.0, height, 0.0, None, found.why_not())
    drives = joint_drives(model)
    wheels = [
        j
        for j in watched_joints(model, passive)
        if int(model.jnt_bodyid[j]) in rolling
        and drives.get(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or "") == "velocity"
    ]
    watched = [j for j in watched_joints(model, passive) if j not in wheels]
    start = data.xpos[root][:2].copy()
    addresses = np.array([model.jnt_qposadr[j] for j in watched], dtype=int)
    home = data.qpos.copy()
    # Each step's state is copied into arrays and judged after the loop: the loop runs
    # 1,500-2,500 times a trial, and judging each step in Python cost as much as stepping.
    steps = round(seconds / model.opt.timestep)
    qpos = np.empty((steps, model.nq))
    base = np.empty((steps, 4))  # the root body's position and its z axis's world z
    for step in range(steps):
        mujoco.mj_step(model, data)
        qpos[step] = data.qpos
        base[step, :3] = data.xpos[root]
        base[step, 3] = data.xmat[root][8]
    judged = _judge(qpos, base, start, home, addresses, (height, floor_height(model)), root)
    tilt, sink, roll, worst, worst_index = judged
    worst_joint = (
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, watched[worst_index])
        if worst_index is not None
        else None
    )
    names = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or "" for j in wheels]
    kvs = [
        float(model.actuator_gainprm[a][0])
        for a in range(model.nu)
        if model.actuator_trntype[a] == mujoco.mjtTrn.mjTRN_JOINT
        and int(model.actuator_trnid[a][0]) in wheels
    ]
    return StandTest(
        seconds,
        tilt,
        sink,
        height,
        worst,
        worst_joint,
        "",
        found.margin,
        names,
        roll,
        min(kvs, default=0.0),
    )


def _judge(qpos, base, start, home, addresses, heights: tuple[float, float], root: int):
    """The largest tilt, sink (below ``heights``: the base's at home above the floor, and the
    floor's) and roll of the base and the largest deviation of a watched
    joint from ``home`` (with the index of its joint in ``addresses``, None if none moved),
    over the steps recorded in ``qpos`` and ``base``, up to the first step whose qpos is not
    finite (the simulation diverged: the tilt is then pi, a fall)."""
    import numpy as np

    finite = np.all(np.isfinite(qpos), axis=1)
    diverged = not finite.all()
    # After mj_step, the bodies' poses are those of the qpos the step started from: a step
    # that diverged still moved the base to finite poses, which count.
    end = int(np.argmin(finite)) if diverged else len(qpos)
    seen = base[: end + 1]
    tilt = math.pi if diverged else 0.0
    if root and len(seen) and not diverged:
        tilt = _tilt(float(np.fmin.reduce(seen[:, 3])))
    height, floor = heights
    sink = float(np.fmax.reduce(height - (seen[:, 2] - floor), initial=0.0))
    moved = np.linalg.norm(seen[:, :2] - start, axis=1)
    roll = float(np.fmax.reduce(moved, initial=0.0))
    worst, worst_index = 0.0, None
    # The step that diverged counts too where the joints watched are still finite.
    counted = end + 1 if diverged and np.all(np.isfinite(qpos[end, addresses])) else end
    if len(addresses) and counted:
        deviation = np.abs(qpos[:counted, addresses] - home[addresses])
        largest = deviation.max(axis=1)
        first = int(np.argmax(largest))  # the step the largest deviation was first reached
        if largest[first] > 0.0:
            worst_index = int(np.argmax(deviation[first]))
            worst = float(deviation[first, worst_index])
    return tilt, sink, roll, worst, worst_index


def joint_drives(model) -> dict[str, str]:
    """Each actuated joint's actuator kind, as mujoco_ros2_control classifies it by the bias:
    'motor' (a torque motor), 'position', 'velocity' or 'custom'."""
    import mujoco

    from mjcfbuild.inputs.ros2_control import runtime_actuator_kind

    drives = {}
    for actuator in range(model.nu):
        if model.actuator_trntype[actuator] != mujoco.mjtTrn.mjTRN_JOINT:
            continue
        joint = mujoco.mj_id2name(
            model, mujoco.mjtObj.mjOBJ_JOINT, model.actuator_trnid[actuator][0]
        )
        biasprm = tuple(float(v) for v in model.actuator_biasprm[actuator][:3])
        drives[joint or ""] = runtime_actuator_kind(int(model.actuator_biastype[actuator]), biasprm)
    return drives


def watched_joints(model, passive: set[str]) -> list[int]:
    """The hinge and slide joints an actuator holds (not asked to be passive)."""
    import mujoco

    return [
        j
        for j in range(model.njnt)
        if mujoco.mjtJoint(model.jnt_type[j])
        in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)
        and (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or "") not in passive
    ]


def free_body(model) -> int:
    """The body of the first free joint (0, the world, without one)."""
    import mujoco

    for joint in range(model.njnt):
        if model.jnt_type[joint] == mujoco.mjtJoint.mjJNT_FREE:
            return int(model.jnt_bodyid[joint])
    return 0


def floor_height(model) -> float:
    """The height of the world's first plane (0 without one)."""
    import mujoco

    for geom in range(model.ngeom):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_PLANE and model.geom_bodyid[geom] == 0:
            return float(model.geom_pos[geom][2])
    return 0.0


def base_tilt(model, data) -> float:
    """The angle between the first free body's up axis and the world's (0 without one)."""
    import mujoco

    for joint in range(model.njnt):
        if model.jnt_type[joint] == mujoco.mjtJoint.mjJNT_FREE:
            return _tilt(data.xmat[model.jnt_bodyid[joint]][8])
    return 0.0


def _tilt(up: float) -> float:
    """The angle whose cosine is ``up`` (a body's z axis's world z component)."""
    return float(math.acos(max(-1.0, min(1.0, up))))


def round_up(value: float) -> str:
    """``value`` rounded up to two significant digits, with a fifth more for margin."""
    digits = f"{value * 1.2:.2g}"
    return digits if float(digits) >= value * 1.2 else f"{float(digits) * 1.1:.2g}"
