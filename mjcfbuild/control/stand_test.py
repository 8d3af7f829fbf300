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
    roll = 0.0
    addresses = np.array([model.jnt_qposadr[j] for j in watched], dtype=int)
    home = data.qpos.copy()
    tilt = sink = worst = 0.0
    worst_joint = None
    # What base_tilt and floor_height look up, once: the loop runs 1,500 times a trial.
    floor = floor_height(model)
    for _ in range(round(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)
        if root:  # base_tilt of the free body (the world's is 0)
            tilt = max(tilt, _tilt(data.xmat[root][8]))
        sink = max(sink, height - (float(data.xpos[root][2]) - floor))
        roll = max(roll, float(np.linalg.norm(data.xpos[root][:2] - start)))
        if len(addresses):
            deviation = np.abs(data.qpos[addresses] - home[addresses])
            index = int(np.argmax(deviation))
            if deviation[index] > worst:
                worst = float(deviation[index])
                worst_joint = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, watched[index])
        if not np.all(np.isfinite(data.qpos)):
            tilt = math.pi
            break
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
