"""Checks that a model is ready to simulate and control.

- every moving joint is driven by exactly one actuator (mimic followers and joints asked to be
  passive excepted);
- a floating robot's lowest collision geometry rests on the floor at home (within 1 mm);
- a fixed-base robot holding its home ``ctrl`` for 1 s stays near home;
- a floating robot that can stand (its feet span an area its centre of mass lies over) stands:
  holding home's ``ctrl`` for 5 s from home, its base stays upright and at height and every
  joint within the hold tolerance; one that cannot (point feet, two wheels on an axle, no
  contact with the floor) is reported as needing a controller, and does not fail;
- MuJoCo Menagerie's model test: 1 s of pseudorandom control over each actuator's ctrlrange
  (a Halton sequence), no MuJoCo warning, finite state.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

from mjcfbuild.check.results import (
    Actuation,
    CheckResults,
    FloorGap,
    Hold,
    MenagerieResult,
    Stand,
)
from mjcfbuild.check.simulation import dof_joint
from mjcfbuild.control.stand_test import (
    base_tilt,
    floor_height,
    joint_drives,
    round_up,
    stand_test,
    watched_joints,
)
from mjcfbuild.mjstopped import SimulationStopped, simulating

FLOOR_TOLERANCE = 1e-3  # m
TEST_SECONDS = 1.0


@dataclass
class ControlReport:
    """The results with the control checks' sections added, and what the Menagerie test
    measured for the speed bound (check.speeds), which check.json does not hold."""

    results: CheckResults = field(default_factory=CheckResults)
    top_speeds: dict[str, float] = field(default_factory=dict)

    @property
    def failures(self) -> list[str]:
        """Every failure so far."""
        return self.results.failures

    def add(self, failures: Sequence[str] = (), **sections) -> None:
        """Add sections and failures to the results."""
        self.results = self.results.add(failures, **sections)


def check_control(
    model,
    passive: set[str],
    hold_tolerance: float,
    strict: bool,
    results: CheckResults | None = None,
) -> ControlReport:
    """Run every control check on ``model`` (the scene), adding their sections to ``results``.
    Without ``strict`` (a model mjcfbuild did not build), undriven joints are reported but do
    not fail."""
    import mujoco

    report = ControlReport(results or CheckResults())
    problems = actuation_problems(model, passive)
    report.add(problems if strict else [], actuation=Actuation(model.nu, problems, strict))
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    report.add(home=home >= 0)
    floating = _floating(model)
    if floating and home >= 0:
        gap = floor_gap(model, home)
        report.add(floor=FloorGap(gap))
        if gap is not None and abs(gap) > FLOOR_TOLERANCE:
            report.add(
                [
                    f"at home the robot's lowest collision geometry is {gap * 1000:.1f} mm "
                    f"{'above' if gap > 0 else 'below'} the floor (tolerance 1 mm)"
                ]
            )
    try:
        _hold_and_stand(model, home, passive, hold_tolerance, floating, report)
    except SimulationStopped as stop:
        report.add([stop.line])
    try:
        with simulating("1 s of pseudorandom control (the Menagerie test)"):
            test = menagerie_test(model)
    except SimulationStopped as stop:
        report.add([stop.line])
        return report
    report.top_speeds = test.top_speeds  # issue 33: for the speed bound (check.speeds)
    advice = _unstable_advice(model, test) if test.warnings or not test.finite else ""
    failures = []
    if not test.finite:
        failures.append(f"the state is not finite under 1 s of pseudorandom control{advice}")
    failures += [
        f"MuJoCo warned under pseudorandom control: {warning}{advice}" for warning in test.warnings
    ]
    report.add(
        failures,
        menagerie_test=MenagerieResult(
            warnings=test.warnings,
            finite=test.finite,
            fastest_joint=test.fastest_joint,
            fastest_speed=test.fastest_speed,
            unstable_joint=test.unstable_joint,
        ),
    )
    return report


def _hold_and_stand(
    model, home: int, passive: set[str], hold_tolerance: float, floating: bool, report
) -> None:
    """The hold (fixed base) and stand (floating base) checks from home, into ``report``."""
    if home >= 0:
        with simulating("holding home's ctrl for 1 s"):
            measure = hold_deviation(model, home, passive)
        deviation, joint = measure.deviation, measure.joint
        failed = not floating and deviation > hold_tolerance
        # Joints asked to have no actuator fail nothing, but an arm whose joints sag from
        # home does not hold it: the verdict says so (CheckResults.caveats).
        sags = not floating and measure.passive_deviation > hold_tolerance
        hold = Hold(
            deviation,
            joint,
            floating,
            measure.tilt if floating else None,
            failed,
            held=measure.held_count,
            passive=measure.passive_count,
            passive_deviation=measure.passive_deviation,
            passive_joint=measure.passive_joint,
            passive_sags=sags,
        )
        report.add(hold=hold)
        if failed:
            report.add(
                [
                    f"holding home's ctrl for 1 s, joint '{joint}' moved {deviation:.3g} from "
                    f"home (check.hold_tolerance {hold_tolerance:g}); "
                    + _hold_advice(model, home, joint)
                ]
            )
    if floating and home >= 0:
        with simulating("holding home's ctrl for 5 s standing on the floor"):
            stand = stand_test(model, home, passive)
        standing = Stand(**stand.to_dict())
        motors = torque_motors(model, passive)
        if stand.needs_controller:
            report.add(stand=standing, needs_controller=stand.needs_controller)
        elif stand.fails(hold_tolerance) and motors:
            # A torque motor's constant ctrl cannot hold a pose: no gain fixes that.
            every = len(motors) == len(watched_joints(model, set()))  # none passive either
            why = motors_need_a_controller(motors, every)
            fell = replace(standing, fell_without_controller=why)
            report.add(stand=fell, needs_controller=why)
        elif (
            stand.fails(hold_tolerance)
            and measure.passive_deviation > hold_tolerance
            and measure.deviation <= hold_tolerance  # its servos held: the passive joints fell
        ):
            # Joints robot.yaml asks to leave without an actuator gave way: the stand is not
            # the servos' to keep (nothing holds those joints), as a fixed base's sag is not.
            why = _passive_give_way(measure)
            fell = replace(standing, fell_without_controller=why)
            report.add(stand=fell, needs_controller=why)
        elif stand.fails(hold_tolerance):
            advice = _hold_advice(model, home, stand.joint)
            fallen = replace(standing, failed=True)
            report.add([stand.failure(hold_tolerance, advice)], stand=fallen)
        else:
            report.add(stand=standing)


def torque_motors(model, passive: set[str]) -> list[str]:
    """The watched joints driven by torque motors, in joint order."""
    import mujoco

    drives = joint_drives(model)
    names = [
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or ""
        for j in watched_joints(model, passive)
    ]
    return [name for name in names if drives.get(name) == "motor"]


def _passive_give_way(measure: HoldMeasure) -> str:
    """Why a floating robot with joints left without an actuator fell."""
    count = measure.passive_count
    return (
        f"{count} of its joints {'has' if count == 1 else 'have'} no actuator, as robot.yaml's "
        f"actuators ask, and gave way, up to {measure.passive_deviation:.3g} at "
        f"{measure.passive_joint}, so nothing holds it up: it stands once a controller or an "
        "actuator holds the joints that carry it"
    )


def motors_need_a_controller(motors: list[str], every: bool = False) -> str:
    """Why a robot on torque motors falls at home, and the two ways out (the rule names every
    motor, to be copied as it is; ``every``: they are all of its hinge and slide joints, which
    one pattern names)."""
    shown = ", ".join(motors[:6]) + (f", ... ({len(motors)} in all)" if len(motors) > 6 else "")
    named = '"*"' if every else ", ".join(motors)
    return (
        f"its joints are driven by torque motors ({shown}), whose constant ctrl cannot hold a "
        "pose, so it fell: it stands under a controller that closes the loop (a ros2_control "
        "controller, or mujoco_ros2_control's PIDs); for a passive stand make them position "
        f"servos with a rule (actuators: {{rules: [{{joints: [{named}], "
        "type: position}]}) in a model not meant for mujoco_ros2_control, whose effort "
        "interfaces need the motors"
    )


def _hold_advice(model, key: int, joint: str | None) -> str:
    """What to change when ``joint`` does not hold home: its force limit when gravity at home
    needs more than it allows (both numbers, and the two fixes), else what fits what drives
    it: a position servo can be stiffened, a torque motor or velocity servo cannot hold a
    pose."""
    import mujoco

    drive = joint_drives(model).get(joint or "")
    if drive == "motor":
        stiffen = (
            f"'{joint}' is driven by a torque motor, whose constant ctrl cannot hold a pose: "
            "hold it with a controller, or make it a position servo with a rule (actuators: "
            f"{{rules: [{{joints: [{joint}], type: position}}]}})"
        )
    elif drive == "velocity":
        stiffen = (
            f"'{joint}' is driven by a velocity servo, which holds a speed, not a position: "
            "where it must hold a pose, make it a position servo with a rule (actuators: "
            f"{{rules: [{{joints: [{joint}], type: position}}]}}); where a <ros2_control> "
            "velocity interface must command it (mujoco_ros2_control takes velocity on a "
            "velocity servo only, or with PID gains), it holds under a controller alone: "
            "raise check.hold_tolerance to say so"
        )
    elif f"joint '{joint}' has no actuator" in actuation_problems(model, set()):
        return (
            f"'{joint}' has no actuator, so nothing holds it: drive it with one (a position "
            "servo holds a pose), or leave it passive where it is meant to move freely"
        )
    else:
        stiffen = "stiffen its actuator (actuators.frequency, or kp in a rule)"
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint or "")
    if index < 0:
        return stiffen
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, key)
    mujoco.mj_forward(model, data)
    if drive not in ("motor", "velocity"):
        aim = _position_aim(model, data, index)
        if aim is not None:
            target, position = aim
            outside = _outside_ctrlrange(model, index, position)
            if outside is not None:
                return (
                    f"'{joint}' is at {position:.4g} at home, outside its servo's ctrlrange "
                    f"[{outside[0]:.4g}, {outside[1]:.4g}], so the servo pulls it back: give "
                    "home a position inside the range"
                )
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_KEY, key)
            return (
                f"the '{name}' keyframe's ctrl asks the servo of '{joint}' for {target:.4g}, "
                f"not its position there ({position:.4g}): give the keyframe a ctrl that "
                "matches its qpos, or remove the keyframe from the inputs and let mjcfbuild "
                "write one"
            )
    if _floating(model):
        from mjcfbuild.control.apply import standing_torques

        load = abs(float(standing_torques(model, data)[model.jnt_dofadr[index]]))
    else:
        load = abs(float(data.qfrc_bias[model.jnt_dofadr[index]]))
    limit = _force_limit(model, index)
    if limit is None or load <= limit:
        return stiffen
    return (
        f"gravity at home needs {load:.3g} N m at '{joint}' but its force limit is "
        f"{limit:.3g}: raise it with a rule (actuators: {{rules: [{{joints: [{joint}], "
        f"forcerange: [-{round_up(load)}, {round_up(load)}]}}]}}) or, where the real robot "
        f"carries this load with a spring or counterweight, compensate gravity on the bodies "
        f"it moves (a rule's gravcomp: true)"
    )


def _position_aim(model, data, joint: int) -> tuple[float, float] | None:
    """Where the servo on ``joint`` aims with the ctrl of ``data`` and the joint's length there
    (its position times the gear), where the two differ by more than a rounding; None where
    they agree or the joint's actuator is no servo with position feedback. A drive's position
    servo (``<dcmotor input="pos">``, mjcfbuild's default) aims at its ctrl; an affine one
    where its force, gain * ctrl + bias0 + bias1 * length, is zero (a ``<position>``: at its
    ctrl)."""
    import mujoco

    from mjcfbuild.actuators import is_dcmotor

    for actuator in range(model.nu):
        if (
            model.actuator_trntype[actuator] != mujoco.mjtTrn.mjTRN_JOINT
            or model.actuator_trnid[actuator][0] != joint
        ):
            continue
        ctrl = float(data.ctrl[actuator])
        gain = float(model.actuator_gainprm[actuator][0])
        bias0, bias1 = (float(v) for v in model.actuator_biasprm[actuator][:2])
        affine = model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE
        if is_dcmotor(model, actuator):
            aim = ctrl
        elif affine and bias1 < 0 and gain > 0:
            aim = (gain * ctrl + bias0) / -bias1
        else:
            return None
        length = float(data.actuator_length[actuator])
        return (aim, length) if abs(aim - length) > 1e-3 * max(1.0, abs(length)) else None
    return None


def _outside_ctrlrange(model, joint: int, length: float) -> tuple[float, float] | None:
    """The ctrlrange of the servo on ``joint`` where ``length`` lies outside it, else None."""
    import mujoco

    for actuator in range(model.nu):
        if (
            model.actuator_trntype[actuator] == mujoco.mjtTrn.mjTRN_JOINT
            and model.actuator_trnid[actuator][0] == joint
            and model.actuator_ctrllimited[actuator]
        ):
            low, high = (float(v) for v in model.actuator_ctrlrange[actuator])
            if not low - 1e-9 <= length <= high + 1e-9:
                return low, high
    return None


def _force_limit(model, joint: int) -> float | None:
    """The smallest force limit on ``joint``: its own, or its actuator's."""
    import mujoco

    limits = []
    if model.jnt_actfrclimited[joint]:
        limits.append(float(max(abs(v) for v in model.jnt_actfrcrange[joint])))
    for actuator in range(model.nu):
        if (
            model.actuator_trntype[actuator] == mujoco.mjtTrn.mjTRN_JOINT
            and model.actuator_trnid[actuator][0] == joint
            and model.actuator_forcelimited[actuator]
        ):
            gear = abs(float(model.actuator_gear[actuator][0])) or 1.0
            limits.append(float(max(abs(v) for v in model.actuator_forcerange[actuator])) * gear)
    return min(limits) if limits else None


def _unstable_advice(model, test: MenagerieTest) -> str:
    """Which joint ran away under the pseudorandom control, its actuator's force limit, and
    what to change; '' when no joint stands out."""
    import mujoco

    if test.unstable_joint is not None:
        name, where = test.unstable_joint, f"at joint '{test.unstable_joint}'"
    elif test.fastest_joint is not None:
        name = test.fastest_joint
        where = f"joint '{name}' reached {test.fastest_speed:.3g} rad/s"
    else:
        return ""
    joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
    limit = ""
    for actuator in range(model.nu):
        if (
            model.actuator_trntype[actuator] == mujoco.mjtTrn.mjTRN_JOINT
            and model.actuator_trnid[actuator][0] == joint
            and model.actuator_forcelimited[actuator]
        ):
            low, high = model.actuator_forcerange[actuator]
            limit = f", its actuator's force range [{low:g}, {high:g}]"
    return (
        f" ({where}{limit}); if "
        "the URDF's effort or range is a placeholder, give the real one (a rule's forcerange "
        "in actuators:), or lower actuators.frequency"
    )


def actuation_problems(model, passive: set[str]) -> list[str]:
    """Moving joints with no actuator, or with more than one."""
    import mujoco

    drivers: dict[int, list[str]] = {}
    for actuator in range(model.nu):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, actuator) or f"#{actuator}"
        target = model.actuator_trnid[actuator, 0]
        kind = mujoco.mjtTrn(model.actuator_trntype[actuator])
        if kind in (mujoco.mjtTrn.mjTRN_JOINT, mujoco.mjtTrn.mjTRN_JOINTINPARENT):
            drivers.setdefault(int(target), []).append(name)
        elif kind == mujoco.mjtTrn.mjTRN_TENDON:
            for joint in _tendon_joints(model, target):
                drivers.setdefault(joint, []).append(name)
    followers = {
        int(model.eq_obj1id[e])
        for e in range(model.neq)
        if model.eq_type[e] == mujoco.mjtEq.mjEQ_JOINT
    }
    problems = []
    for joint in range(model.njnt):
        if model.jnt_type[joint] == mujoco.mjtJoint.mjJNT_FREE or joint in followers:
            continue
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, joint) or f"#{joint}"
        found = drivers.get(joint, [])
        if not found and name not in passive:
            problems.append(f"joint '{name}' has no actuator")
        elif len(found) > 1:
            problems.append(
                f"joint '{name}' is driven by {len(found)} actuators ({', '.join(found)})"
            )
    return problems


def floor_gap(model, key: int) -> float | None:
    """Height of the lowest robot collision point above the scene's floor, at keyframe ``key``."""
    import mujoco

    from mjcfbuild.control.floor import lowest_collision_point

    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, key)
    mujoco.mj_kinematics(model, data)
    lowest = lowest_collision_point(model, data)
    if lowest is None:
        return None
    return lowest.height - floor_height(model)


@dataclass
class HoldMeasure:
    """What 1 s of home's ctrl did: the largest distance from home of a hinge or slide joint
    an actuator holds and its joint, the same of the joints asked to be passive (no
    actuator), how many of those there are, and how far a floating base tilted by the end
    (rad; a robot that does not stand in its home pose falls over)."""

    deviation: float
    joint: str | None
    passive_deviation: float
    passive_joint: str | None
    passive_count: int
    tilt: float
    held_count: int = 0  # the hinge and slide joints not asked to be passive


def hold_deviation(model, key: int, passive: set[str]) -> HoldMeasure:
    """Hold home's ctrl for 1 s from keyframe ``key``: how far the joints moved."""
    import mujoco

    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, key)
    home = data.qpos.copy()
    held = _Farthest(model, watched_joints(model, passive))
    unheld = _Farthest(model, [j for j in watched_joints(model, set()) if j not in held.joints])
    for _ in range(round(TEST_SECONDS / model.opt.timestep)):
        mujoco.mj_step(model, data)
        held.note(data.qpos, home)
        unheld.note(data.qpos, home)
    return HoldMeasure(
        held.distance,
        held.name(model),
        unheld.distance,
        unheld.name(model),
        len(unheld.joints),
        base_tilt(model, data),
        len(held.joints),
    )


class _Farthest:
    """The farthest any of ``joints`` (hinge and slide joint ids of ``model``) got from home."""

    def __init__(self, model, joints: list[int]) -> None:
        self.joints = joints
        self.addresses = model.jnt_qposadr[joints]
        self.distance = 0.0
        self.joint: int | None = None

    def note(self, qpos, home) -> None:
        """Take the joints' positions ``qpos`` into account."""
        import numpy as np

        if not self.joints:
            return
        deviation = np.abs(qpos[self.addresses] - home[self.addresses])
        index = int(np.argmax(deviation))
        if deviation[index] > self.distance:
            self.distance = float(deviation[index])
            self.joint = self.joints[index]

    def name(self, model) -> str | None:
        """The farthest joint's name (None where none moved)."""
        import mujoco

        if self.joint is None:
            return None
        return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, self.joint)


@dataclass
class MenagerieTest:
    """What 1 s of pseudorandom control did: MuJoCo's warnings (as 'name (xN)'), whether the
    state stayed finite, the fastest hinge or slide joint with its top speed (before any
    reset), and the joint of an unstable acceleration."""

    warnings: list[str]
    finite: bool
    fastest_joint: str | None
    fastest_speed: float
    unstable_joint: str | None  # where MuJoCo found an unstable acceleration, if it did
    top_speeds: dict[str, float] = field(default_factory=dict)  # issue 33: joint -> top speed


def menagerie_test(model, qpos=None) -> MenagerieTest:
    """1 s of Halton-sequence control over each ctrlrange from the default state (or from it
    with ``qpos``)."""
    import mujoco
    import numpy as np

    data = mujoco.MjData(model)
    mujoco.mj_resetData(model, data)
    if qpos is not None:
        data.qpos[:] = qpos
    centre = np.zeros(model.nu)
    radius = np.ones(model.nu)
    limited = model.actuator_ctrllimited.astype(bool)
    ranges = model.actuator_ctrlrange
    centre[limited] = ranges[limited].mean(axis=1)
    radius[limited] = (ranges[limited, 1] - ranges[limited, 0]) / 2
    # The joints' own speeds (hinges and slides): a free base tumbling is a consequence.
    jointed = np.isin(
        model.jnt_type[model.dof_jntid], [mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE]
    )
    top = np.zeros(model.nv)
    step = 0
    finite = True
    # MuJoCo resets an unstable simulation to time 0 (with a warning): count steps instead.
    steps = math.ceil(TEST_SECONDS / model.opt.timestep)
    while step < steps:
        for actuator in range(model.nu):
            halton = mujoco.mju_Halton(step, actuator + 2)
            data.ctrl[actuator] = centre[actuator] + radius[actuator] * (2 * halton - 1)
        mujoco.mj_step(model, data)
        step += 1
        if not (np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))):
            finite = False
            break
        np.maximum(top, np.abs(data.qvel), out=top)
        if data.warning.number.any():  # one array read; a loop over the stats costs 0.1 s
            break
    warnings = [
        f"{mujoco.mjtWarning(index).name.removeprefix('mjWARN_').lower()} (x{int(stat.number)})"
        for index, stat in enumerate(data.warning)
        if stat.number
    ]
    fastest_joint, fastest_speed = None, 0.0
    if jointed.any():
        dof = int(np.argmax(np.where(jointed, top, -1.0)))
        fastest_joint = dof_joint(model, dof)
        fastest_speed = float(top[dof])
    # MuJoCo records the DOF of an unstable acceleration: named if it is a joint's own (on a
    # free base it is the base, which only carries what the legs did; the fastest joint says
    # more then).
    unstable = data.warning[mujoco.mjtWarning.mjWARN_BADQACC]
    dof = int(unstable.lastinfo)
    own = unstable.number and 0 <= dof < model.nv and jointed[dof]
    unstable_joint = dof_joint(model, dof) if own else None
    tops = {dof_joint(model, int(d)) or f"#{d}": float(top[d]) for d in np.flatnonzero(jointed)}
    return MenagerieTest(warnings, finite, fastest_joint, fastest_speed, unstable_joint, tops)


def outside_at_qpos0(model) -> tuple[list[str], list[float]]:
    """The limited hinges and slides whose qpos0 lies outside their range, and qpos0 with
    each of them clipped into its range."""
    import mujoco

    qpos = [float(value) for value in model.qpos0]
    outside = []
    hinged = {int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)}
    for joint in range(model.njnt):
        if int(model.jnt_type[joint]) not in hinged or not model.jnt_limited[joint]:
            continue
        low, high = (float(bound) for bound in model.jnt_range[joint])
        address = int(model.jnt_qposadr[joint])
        if not low <= qpos[address] <= high:
            outside.append(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, joint) or "")
            qpos[address] = min(max(qpos[address], low), high)
    return outside, qpos


def _floating(model) -> bool:
    import mujoco

    return any(model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE for j in range(model.njnt))


def _tendon_joints(model, tendon: int) -> list[int]:
    import mujoco

    start, count = model.tendon_adr[tendon], model.tendon_num[tendon]
    return [
        int(model.wrap_objid[w])
        for w in range(start, start + count)
        if model.wrap_type[w] == mujoco.mjtWrap.mjWRAP_JOINT
    ]
