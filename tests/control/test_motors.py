"""Motors: a drive's armature, force limit and torque-speed line in the compiled model; gear
ratios from <transmission>; users' motor files; the catalogue's sources; bad motor settings."""

from __future__ import annotations

import json
import re

import mujoco
import numpy as np
import pytest
import yaml

import mjcfbuild
from mjcfbuild.check.tuning import stand_spec
from mjcfbuild.control.catalogue import SHIPPED, shipped_motors
from tests.conftest import run_cli, two_link_urdf, write
from tests.control.quadruped import MANIFEST, quadruped_urdf

GO1_ROTOR = 0.000111842  # the catalogue's go1 rotor inertia, kg m^2
KNEE_RATIO, KNEE_PEAK, KNEE_NO_LOAD = 9, 35.55, 20.06

RULES = """actuators:
  rules:
    - {joints: ["*_calf_joint"], motor: go1_knee}
    - {joints: ["*_hip_joint", "*_thigh_joint"], motor: go1_hip}
"""


def _build(folder, manifest_extra: str = RULES, transmission: float | None = None):
    write(folder / "robot.urdf", quadruped_urdf(transmission))
    write(folder / "robot.yaml", MANIFEST + manifest_extra)
    result = mjcfbuild.build(folder / "robot.yaml")
    assert not result.errors, result.errors
    return result


def _ids(model, joint: str) -> tuple[int, int]:
    """The dof and the actuator of ``joint``."""
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
    actuators = [a for a in range(model.nu) if model.actuator_trnid[a, 0] == index]
    assert len(actuators) == 1
    return int(model.jnt_dofadr[index]), actuators[0]


KNEES = [f"{leg}_calf_joint" for leg in ("FL", "FR", "RL", "RR")]


def test_a_quadruped_with_motors_has_their_armature_force_limit_and_speed_line(tmp_path):
    result = _build(tmp_path)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    for knee in KNEES:
        dof, actuator = _ids(model, knee)
        assert model.dof_armature[dof] == pytest.approx(GO1_ROTOR * KNEE_RATIO**2, abs=1e-9)
        assert model.actuator_forcelimited[actuator]
        assert list(model.actuator_forcerange[actuator]) == pytest.approx([-KNEE_PEAK, KNEE_PEAK])
        # At full command, the torque the drive gives at a speed is on the no-load-speed line.
        data = mujoco.MjData(model)
        mujoco.mj_resetDataKeyframe(model, data, 0)
        for share in (0.0, 0.25, 0.5, 0.75, 0.95, 1.0, 1.1):
            data.qvel[:] = 0
            data.qvel[dof] = share * KNEE_NO_LOAD
            data.ctrl[actuator] = model.actuator_ctrlrange[actuator][1] + 10  # clamped: far
            mujoco.mj_forward(model, data)
            line = KNEE_PEAK * (1 - share)  # the stall torque is the peak (no torque constant)
            assert data.actuator_force[actuator] == pytest.approx(line, abs=1e-6), share
    record = json.loads((tmp_path / "mjcf/.mjcfbuild/assembly.json").read_text())["readiness"]
    knee = next(a for a in record["actuators"] if a["joint"] == "FL_calf_joint")
    assert knee["type"] == "dcmotor" and knee["motor"]["motor"] == "go1_knee"


def test_a_knee_at_full_torque_stays_under_its_no_load_speed(tmp_path):
    result = _build(tmp_path)
    spec = mujoco.MjSpec.from_file(str(result.robot))
    stand_spec(spec)  # base held, contacts off
    spec.option.gravity = [0, 0, 0]
    model = spec.compile()
    dof, actuator = _ids(model, "FL_calf_joint")
    data = mujoco.MjData(model)
    data.qpos[dof] = -2.7  # one end of its range; commanded to the other
    data.ctrl[actuator] = -0.9
    top, points = 0.0, []
    for _ in range(200):
        before = float(data.qvel[dof])  # the speed the step's force is computed at
        mujoco.mj_step(model, data)
        top = max(top, abs(float(data.qvel[dof])))
        points.append((before, float(data.actuator_force[actuator])))
    # Full torque accelerates it close to the no-load speed, never past it...
    assert 0.8 * KNEE_NO_LOAD < top <= KNEE_NO_LOAD * (1 + 1e-6)
    # ... and the torque that drives it is under the line at every speed it reached (braking
    # torque, against the motion, is bounded by the peak torque only).
    driving = [(abs(v), abs(f)) for v, f in points if v * f > 0]
    assert driving
    for speed, force in driving:
        assert force <= KNEE_PEAK * (1 - speed / KNEE_NO_LOAD) + 1e-6
    assert max(abs(f) for _, f in points) <= KNEE_PEAK + 1e-9


def test_gains_are_sized_from_the_inertia_with_armature(tmp_path):
    # Not checked: 10 Hz calves are too soft to hold the standing robot, which the stand test
    # says; the gains are this test's subject.
    result = _build(
        tmp_path,
        RULES.replace("motor: go1_knee}", "motor: go1_knee, frequency: 10}")
        + "check: {enabled: false}\n",
    )
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)
    dof, actuator = _ids(model, "FL_calf_joint")
    assert full[dof, dof] > GO1_ROTOR * KNEE_RATIO**2  # the rotor is part of it
    kp = model.actuator_gainprm[actuator][4]  # the dcmotor controller: kp, ki, kd
    kd = model.actuator_gainprm[actuator][6]
    omega = 2 * np.pi * 10
    assert kp == pytest.approx(full[dof, dof] * omega**2, rel=1e-6)
    assert kd == pytest.approx(2 * full[dof, dof] * omega, rel=1e-6)


def test_a_transmission_reduction_is_the_gear_ratio_of_the_named_motor(tmp_path):
    result = _build(tmp_path, transmission=12)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    dof, _ = _ids(model, "RR_calf_joint")
    assert model.dof_armature[dof] == pytest.approx(GO1_ROTOR * 12**2, abs=1e-9)
    notes = [w for w in result.warnings if "replaces the ratio 9 of motor 'go1_knee'" in w]
    assert len(notes) == 4 and "reduction 12" in notes[0], result.warnings


def test_a_reduction_without_a_motor_is_reported(tmp_path):
    result = _build(tmp_path, "", transmission=50)
    unused = [w for w in result.warnings if "<transmission> reduction of 50 but no motor" in w]
    assert len(unused) == 4, result.warnings
    assert re.search(r"robot\.urdf:\d+: joint 'FL_calf_joint'", unused[0]), unused[0]


def _one_calf_motor(urdf: str, follower_interface: str) -> str:
    """Every calf's transmission on FL's actuator, the other three with ``follower_interface``."""
    for leg in ("FR", "RL", "RR"):
        urdf = urdf.replace(f'"{leg}_calf_motor"', '"FL_calf_motor"')
        urdf = urdf.replace(
            f'<joint name="{leg}_calf_joint"><hardwareInterface>hardware_interface/'
            "EffortJointInterface",
            f'<joint name="{leg}_calf_joint"><hardwareInterface>hardware_interface/'
            f"{follower_interface}",
        )
    return urdf


def test_joints_one_actuator_moves_and_only_reads_are_one_warning_and_no_gear_ratio(tmp_path):
    # An underactuated mechanism: one motor behind every calf, commanding FL's and only
    # reading the others (as TIAGo's Hey5 hand's one motor curls many finger joints). The
    # followers' reductions are ratios between the joints, not gearboxes.
    urdf = _one_calf_motor(quadruped_urdf(50), "JointStateInterface")
    assert urdf.count('"FL_calf_motor"') == 4 and urdf.count("JointStateInterface") == 3
    write(tmp_path / "robot.urdf", urdf)
    write(tmp_path / "robot.yaml", MANIFEST + RULES)
    result = mjcfbuild.build(tmp_path / "robot.yaml")
    assert not result.errors, result.errors
    mechanism = [w for w in result.warnings if "underactuated" in w]
    assert len(mechanism) == 1, result.warnings
    assert re.match(
        r"robot\.urdf:\d+: <transmission>s of type 'transmission_interface/SimpleTransmission' "
        r"move 4 joints from 'FL_calf_joint' by actuator 'FL_calf_motor': an underactuated "
        r"mechanism the model does not reproduce",
        mechanism[0],
    ), mechanism[0]
    # FL's transmission commands it: its reduction is its motor's gear ratio, as before.
    assert [w for w in result.warnings if "replaces the ratio 9" in w] == [
        next(w for w in result.warnings if "joint 'FL_calf_joint'" in w)
    ]
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.dof_armature[_ids(model, "FL_calf_joint")[0]] == pytest.approx(
        GO1_ROTOR * 50**2, abs=1e-9
    )
    for knee in KNEES[1:]:  # the motor's own ratio
        dof, _ = _ids(model, knee)
        assert model.dof_armature[dof] == pytest.approx(GO1_ROTOR * KNEE_RATIO**2, abs=1e-9)


def test_one_actuator_name_on_joints_each_commands_is_no_mechanism(tmp_path):
    # A copied name (pybullet's xArm: joint3 and joint4 on motor3), each transmission
    # commanding its joint: four gearboxes, as if the names differed.
    write(tmp_path / "robot.urdf", _one_calf_motor(quadruped_urdf(50), "EffortJointInterface"))
    write(tmp_path / "robot.yaml", MANIFEST + RULES)
    result = mjcfbuild.build(tmp_path / "robot.yaml")
    assert not result.errors, result.errors
    assert not [w for w in result.warnings if "underactuated" in w], result.warnings
    assert len([w for w in result.warnings if "replaces the ratio 9" in w]) == 4


def test_which_transmissions_make_an_underactuated_mechanism():
    from mjcfbuild.control.motors import reductions, underactuated
    from mjcfbuild.inputs.ros2_control import Transmission

    state = ["hardware_interface/JointStateInterface"]
    command = ["hardware_interface/PositionJointInterface"]

    def joint(name, interfaces, actuators, element, reduction=2.0):
        return Transmission(name, interfaces, f"r.urdf:{element}", reduction, actuators, element)

    wrist = [  # one element, two motors, two joints: fully actuated
        joint("pitch", command, ["m6", "m7"], "w"),
        joint("roll", command, ["m6", "m7"], "w"),
    ]
    hand = [  # one motor commanding one joint, moving two more it only reads
        joint("knuckle", command, ["m1"], "h1", reduction=None),
        joint("f1", state, ["m1"], "h2", 0.1),
        joint("f2", state, ["m1"], "h3", 0.2),
    ]
    linkage = [  # ros2_control: one element of three joints and one actuator
        joint("a", [], ["m9"], "l", 3.0),
        joint("b", [], ["m9"], "l"),
        joint("c", [], ["m9"], "l"),
    ]
    unnamed = [joint("u1", [], [], "u"), joint("u2", [], [], "u")]  # no actuator named
    alone = [joint("s", [], [], "s")]  # one joint is never a mechanism
    everything = wrist + hand + linkage + unnamed + alone
    names = {t.joint for t in everything}
    assert underactuated(everything, names) == [hand, linkage, unnamed]
    assert underactuated(everything, names - {"f2"}) == [hand[:2], linkage, unnamed]
    assert underactuated(everything, names - {"f1", "f2"}) == [linkage, unnamed]
    # The read-only joints' reductions are no gear ratios; the commanding joints' are.
    found = underactuated(everything, names)
    assert sorted(reductions(everything, found)) == [
        "a",
        "b",
        "c",
        "pitch",
        "roll",
        "s",
        "u1",
        "u2",
    ]


def test_a_users_motor_file_and_definitions_extend_the_catalogue(tmp_path):
    write(
        tmp_path / "drives.yaml",
        "# a drive of our own\nbig:\n  rotor_inertia: 2.0e-4\n  ratio: 10\n  peak_torque: 50\n",
    )
    extra = (
        "motors:\n  files: [drives.yaml]\n  define:\n"
        "    small: {rotor_inertia: 1.0e-5, ratio: 4, at: rotor, peak_torque: 2, friction: 0.3,"
        " damping: 0.05}\n"
        "actuators:\n  rules:\n"
        '    - {joints: ["*_calf_joint"], motor: big}\n'
        '    - {joints: ["*_hip_joint", "*_thigh_joint"], motor: small}\n'
    )
    result = _build(tmp_path, extra)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    dof, actuator = _ids(model, "FL_calf_joint")
    assert model.dof_armature[dof] == pytest.approx(2.0e-4 * 100, abs=1e-9)
    assert model.actuator_forcerange[actuator][1] == pytest.approx(50)
    # No speed data: a position servo with the peak torque as its force limit.
    assert model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE
    dof, actuator = _ids(model, "FL_hip_joint")
    assert model.dof_armature[dof] == pytest.approx(1.0e-5 * 16, abs=1e-12)
    assert model.actuator_forcerange[actuator][1] == pytest.approx(8)  # 2 N m at the rotor x 4
    assert model.dof_frictionloss[dof] == pytest.approx(0.3)
    assert model.dof_damping[dof] == pytest.approx(0.05)


def test_every_catalogue_entry_cites_its_datasheet():
    motors = shipped_motors()
    assert {"go1_hip", "go1_knee", "dynamixel_xm430_w350", "maxon_ec45flat70_hd100"} <= set(motors)
    lines = SHIPPED.read_text().splitlines()
    for name, motor in motors.items():
        assert motor.source, name
        start = lines.index(f"{name}:")
        assert lines[start - 1].startswith("# "), f"{name} has no comment naming its datasheet"
    assert yaml.safe_load(SHIPPED.read_text()).keys() == motors.keys()


BAD = {
    "an unknown motor": (
        "actuators:\n  rules:\n    - {joints: [hinge], motor: go7_knee}\n",
        "robot.yaml:5",
        "unknown motor 'go7_knee'; did you mean 'go1_knee'? (use one of dynamixel_xm430_w350, "
        "go1_hip, go1_knee",
    ),
    "a ratio that is not positive": (
        "motors:\n  define:\n    m: {rotor_inertia: 1.0e-5, ratio: 0, peak_torque: 3}\n",
        "robot.yaml:5",
        "motors.define.m.ratio: 0 should be greater than 0",
    ),
    "an inertia that is not positive": (
        "motors:\n  define:\n    m: {rotor_inertia: -1, peak_torque: 3}\n",
        "robot.yaml:5",
        "motors.define.m.rotor_inertia: -1 should be greater than 0",
    ),
    "a misspelt motor key": (
        "motors:\n  define:\n    m: {rotor_inertia: 1.0e-5, peak_torque: 3, ration: 5}\n",
        "robot.yaml:5",
        "motors.define.m.ration: unknown key 'ration'; did you mean 'ratio'?",
    ),
    "a peak torque below the continuous torque": (
        "motors:\n  define:\n    m: {rotor_inertia: 1.0e-5, peak_torque: 3, continuous_torque: 5}"
        "\n",
        "robot.yaml:5",
        "peak_torque 3 is below continuous_torque 5; the peak torque must be at least the "
        "continuous one",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_motor_setting(tmp_path, case):
    extra, where, message = BAD[case]
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + extra)
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == 3, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr
    assert where in lines[0] and message in lines[0], lines[0]
    assert not (tmp_path / "mjcf" / "r.xml").exists()


def test_a_bad_motor_file_names_its_own_line(tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "drives.yaml", "m:\n  rotor_inertia: 1.0e-5\n  peak_torque: 3\n  gear: 5\n")
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\nmotors: {files: [drives.yaml]}\n"
        "actuators:\n  rules:\n    - {joints: [hinge], motor: m}\n",
    )
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == 3, result.stderr
    [line] = result.stderr.strip().splitlines()
    assert "drives.yaml:4" in line and "unknown key 'gear'" in line, line
    assert not (tmp_path / "mjcf" / "r.xml").exists()


def test_the_report_names_each_actuators_motor(tmp_path):
    _build(tmp_path)
    page = (tmp_path / "mjcf/report/report.md").read_text()
    assert "| FL_calf_joint | FL_calf_joint | dcmotor | default, motor go1_knee |" in page


def test_an_edited_motor_file_rebuilds_the_model(tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    drives = write(
        tmp_path / "drives.yaml", "m: {rotor_inertia: 1.0e-4, ratio: 10, peak_torque: 5}\n"
    )
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\nmotors: {files: [drives.yaml]}\n"
        "actuators:\n  rules:\n    - {joints: [hinge], motor: m}\n",
    )
    for ratio in (10, 20):
        drives.write_text(f"m: {{rotor_inertia: 1.0e-4, ratio: {ratio}, peak_torque: 5}}\n")
        result = run_cli("build", "-q", "--no-check", str(tmp_path / "robot.yaml"))
        assert result.code == 0, result.stderr
        model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "r.xml"))
        assert model.dof_armature[0] == pytest.approx(1.0e-4 * ratio**2)
