"""Actuators: from rules, ros2_control, transmissions, the default, and the user's own."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from tests.control.helpers import actuator, build_two_link, load, readiness


def _inertia_at_home(model, joint: str) -> float:
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)
    dof = model.jnt_dofadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)]
    return full[dof, dof]


def test_a_bare_manifest_drives_every_moving_joint_with_a_position_servo(tmp_path):
    """A <dcmotor input="pos">: a position servo whose torque falls from the URDF effort at
    rest to zero at the URDF velocity, on the rotor inertia that keeps that line stable."""
    model = load(build_two_link(tmp_path))
    assert model.nu == 1
    hinge = actuator(model, "hinge")
    assert model.actuator_gaintype[hinge] == mujoco.mjtGain.mjGAIN_DCMOTOR
    joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "hinge")
    # effort 10 N m, velocity 1 rad/s: stall torque / no-load speed x one 2 ms step
    assert model.dof_armature[model.jnt_dofadr[joint]] == pytest.approx(10 / 1 * 0.002)
    inertia = _inertia_at_home(model, "hinge")  # the rotor's included
    omega = 2 * math.pi * 10  # the documented default frequency, critically damped
    kp, kv = model.actuator_gainprm[hinge][4], model.actuator_gainprm[hinge][6]
    assert kp == pytest.approx(inertia * omega**2, rel=1e-9)
    assert kv == pytest.approx(2 * inertia * omega, rel=1e-9)
    assert list(model.actuator_ctrlrange[hinge]) == [-1.5, 1.5]
    assert list(model.actuator_forcerange[hinge]) == [-10, 10]  # the URDF effort
    record = readiness(tmp_path)["actuators"][0]
    assert (record["name"], record["type"], record["source"]) == ("hinge", "dcmotor", "default")
    assert (record["motor"]["stall_torque"], record["motor"]["no_load_speed"]) == (10, 1)
    # the drive's rotor, as the report and check.json state it, is the joint's armature
    assert record["motor"]["armature"] == record["armature"] == pytest.approx(0.02)


def test_speed_limits_off_gives_a_plain_position_servo(tmp_path):
    model = load(build_two_link(tmp_path, "actuators: {speed_limits: false}\n"))
    hinge = actuator(model, "hinge")
    inertia = _inertia_at_home(model, "hinge")
    omega = 2 * math.pi * 10
    assert model.actuator_gainprm[hinge][0] == pytest.approx(inertia * omega**2, rel=1e-9)
    assert -model.actuator_biasprm[hinge][2] == pytest.approx(2 * inertia * omega, rel=1e-9)
    joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "hinge")
    assert model.dof_armature[model.jnt_dofadr[joint]] == 0
    record = readiness(tmp_path)["actuators"][0]
    assert (record["type"], record["motor"]) == ("position", None)


def test_a_rule_sets_type_gains_and_joint_dynamics(tmp_path):
    model = load(
        build_two_link(
            tmp_path,
            "actuators:\n  rules:\n"
            "    - {joints: [hin*], type: velocity, kv: 7, armature: 0.1, damping: 0.5, "
            "frictionloss: 0.2}\n",
        )
    )
    hinge = actuator(model, "hinge")
    assert model.actuator_biasprm[hinge][2] == -7
    assert list(model.actuator_ctrlrange[hinge]) == [-1, 1]  # the URDF velocity limit
    joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "hinge")
    assert model.dof_armature[joint] == 0.1
    assert model.dof_damping[joint] == 0.5
    assert model.dof_frictionloss[joint] == 0.2
    assert readiness(tmp_path)["actuators"][0]["source"] == "rule"


def test_a_rule_without_a_type_only_tunes_the_gains(tmp_path):
    model = load(build_two_link(tmp_path, "actuators:\n  rules: [{joints: [hinge], kp: 321}]\n"))
    hinge = actuator(model, "hinge")
    assert model.actuator_gainprm[hinge][4] == 321  # a <dcmotor>'s kp
    assert readiness(tmp_path)["actuators"][0]["source"] == "default"


@pytest.mark.parametrize(
    ("interfaces", "kind"),
    [
        (["position"], "position"),
        (["velocity"], "velocity"),
        (["effort"], "motor"),
        (["velocity", "position"], "position"),
    ],
)
def test_ros2_control_command_interfaces_decide_the_type(tmp_path, interfaces, kind):
    commands = "".join(f'<command_interface name="{i}"/>' for i in interfaces)
    control = f'<ros2_control name="s" type="system"><joint name="hinge">{commands}</joint></ros2_control>'
    model = load(build_two_link(tmp_path, urdf_extra=control))
    assert model.nu == 1  # never two actuators on one joint
    record = readiness(tmp_path)["actuators"][0]
    # Never a <dcmotor>: mujoco_ros2_control takes one for a custom actuator and refuses a
    # position command on it (tests/check/test_runtime.py).
    assert (record["type"], record["source"]) == (kind, "ros2_control")
    if kind == "motor":
        assert list(model.actuator_ctrlrange[0]) == [-10, 10]


@pytest.mark.parametrize(
    ("interface", "source"),
    [("EffortJointInterface", "transmission"), ("JointStateInterface", "default")],
)
def test_a_ros1_transmission_names_an_actuated_joint(tmp_path, interface, source):
    """Its effort interface is what a ROS controller commands, usually under a position PID;
    without that controller the joint gets the default servo. A transmission that only reads
    the joint (an underactuated hand's finger joints) commands nothing: the default's own."""
    transmission = f"""<transmission name="t"><type>transmission_interface/SimpleTransmission</type>
      <joint name="hinge"><hardwareInterface>hardware_interface/{interface}</hardwareInterface></joint>
      <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>"""
    model = load(build_two_link(tmp_path, urdf_extra=transmission))
    record = readiness(tmp_path)["actuators"][0]
    assert (record["type"], record["source"]) == ("dcmotor", source)
    assert model.actuator_gaintype[0] == mujoco.mjtGain.mjGAIN_DCMOTOR


def test_an_actuator_the_user_wrote_replaces_the_generated_one(tmp_path):
    model = load(
        build_two_link(
            tmp_path,
            'mujoco_inputs:\n  raw: \'<actuator><motor name="mine" joint="hinge"/></actuator>\'\n',
        )
    )
    assert model.nu == 1
    assert mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, 0) == "mine"
    record = readiness(tmp_path)["actuators"][0]
    assert (record["name"], record["source"]) == ("mine", "user")


def test_default_none_gives_a_passive_model_that_still_passes_the_check(tmp_path):
    result = build_two_link(tmp_path, "actuators: {default: none}\n")
    assert load(result).nu == 0
    assert readiness(tmp_path)["passive"] == ["hinge"]


def test_a_continuous_joint_that_is_no_wheel_gets_a_position_servo(tmp_path):
    """Its body is a rod, not round about the axis: a revolving joint, held in position
    (tests/control/test_standing.py has the wheel that gets a velocity servo)."""
    model = load(build_two_link(tmp_path, joint_type="continuous"))
    assert readiness(tmp_path)["actuators"][0]["type"] == "dcmotor"  # input="pos"
    assert not model.actuator_ctrllimited[0]


def test_the_pendulum_rings_at_the_frequency_and_damping_asked_for(tmp_path):
    """Closed loop, measured in simulation: peaks of the step response give the damped
    frequency and the logarithmic decrement gives the damping ratio."""
    frequency, ratio = 2.0, 0.1
    result = build_two_link(
        tmp_path,
        f"actuators:\n  rules: [{{joints: [hinge], frequency: {frequency}, "
        f"damping_ratio: {ratio}, armature: 0.01}}]\n"
        'mujoco_inputs:\n  raw: \'<option gravity="0 0 0" timestep="0.0005"/>\'\n',
    )
    model = load(result)
    data = mujoco.MjData(model)
    data.ctrl[0] = 0.2
    angles = []
    for _ in range(int(3.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
        angles.append(data.qpos[0] - 0.2)
    angles = np.array(angles)
    peaks = [i for i in range(1, len(angles) - 1) if angles[i - 1] < angles[i] >= angles[i + 1]]
    peaks = [i for i in peaks if angles[i] > 0]
    period = (peaks[1] - peaks[0]) * model.opt.timestep
    decrement = math.log(angles[peaks[0]] / angles[peaks[1]])
    measured_ratio = decrement / math.sqrt(4 * math.pi**2 + decrement**2)
    measured_frequency = 1 / period / math.sqrt(1 - measured_ratio**2)
    assert measured_frequency == pytest.approx(frequency, rel=0.1)
    assert measured_ratio == pytest.approx(ratio, rel=0.1)


def test_the_speed_lines_rotor_adds_to_the_armature_the_joint_has(tmp_path):
    model = load(
        build_two_link(
            tmp_path, "mujoco_inputs:\n  raw: '<default><joint armature=\"0.05\"/></default>'\n"
        )
    )
    joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "hinge")
    assert model.dof_armature[model.jnt_dofadr[joint]] == pytest.approx(0.05 + 10 / 1 * 0.002)


def test_a_velocity_servo_reaches_its_command_against_the_joints_damping(tmp_path):
    """kv from the joint's inertia alone (0.04 here) left a wheel with URDF damping 0.2 at a
    sixth of the commanded speed; the servo now dominates the damping (98 %)."""
    from tests.conftest import two_link_urdf, write

    urdf = two_link_urdf(
        extra='<ros2_control name="s" type="system"><hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware><joint name="hinge">'
        '<command_interface name="velocity"/></joint></ros2_control>',
        joint_type="continuous",
    ).replace('<axis xyz="0 1 0"/>', '<axis xyz="0 1 0"/><dynamics damping="0.2"/>')
    write(tmp_path / "robot.urdf", urdf)
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\n"
        "mujoco_inputs:\n  raw: '<option gravity=\"0 0 0\"/>'\n",
    )
    import mjcfbuild

    model = load(mjcfbuild.build(tmp_path / "robot.yaml"))
    assert model.actuator_biastype[0] == mujoco.mjtBias.mjBIAS_AFFINE
    assert model.dof_damping[0] == pytest.approx(0.2)
    data = mujoco.MjData(model)
    data.ctrl[0] = 0.5
    mujoco.mj_step(model, data, int(2.0 / model.opt.timestep))
    assert data.qvel[0] == pytest.approx(0.5, rel=0.03)
