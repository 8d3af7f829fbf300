"""Robots a controller author can use: they stand, hold, and are driven by what their joints are.

Each robot is generated (primitives only), built by the real build, compiled and simulated by
MuJoCo; the stand test is the check's own, and each test reads the model, not the report.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import mujoco
import numpy as np
import pytest

import mjcfbuild
from mjcfbuild.control.standing import MARGIN
from mjcfbuild.errors import BuildFailed
from tests.conftest import run_cli, two_link_urdf, write
from tests.control import robots
from tests.control.helpers import actuator, build_two_link, load, readiness

pytestmark = pytest.mark.slow  # each builds and simulates a robot for 5 s


def _build(folder: Path, urdf: str, manifest: str = "", free_joint: bool = True):
    write(folder / "urdf/robot.urdf", urdf)
    write(
        folder / "robot.yaml",
        "name: r\nsource: {urdf: urdf/robot.urdf}\n"
        f"options: {{free_joint: {'true' if free_joint else 'false'}}}\n" + manifest,
    )
    return mjcfbuild.build(folder / "robot.yaml", jobs=1)


def _check(folder: Path) -> dict:
    return json.loads((folder / "mjcf/.mjcfbuild/check.json").read_text())


def _scene(folder: Path) -> tuple[mujoco.MjModel, mujoco.MjData]:
    model = mujoco.MjModel.from_xml_path(str(folder / "mjcf/scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    return model, data


def _hold(model, data, seconds: float) -> None:
    for _ in range(round(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)


def _tilt(data) -> float:
    return float(np.arccos(np.clip(data.xmat[1].reshape(3, 3)[2, 2], -1, 1)))


STANDING_SRDF = """<?xml version="1.0"?>
<robot name="quad">
  <virtual_joint name="root_joint" type="floating" parent_frame="world" child_link="trunk"/>
  <group_state name="straight" group="all">{straight}</group_state>
  <group_state name="standing" group="all">
    <joint name="root_joint" value="0 0 0.3 0 0 0 1"/>{bent}
  </group_state>
</robot>
"""


def test_a_quadruped_stands_in_the_srdf_pose_shipped_beside_its_description(tmp_path):
    """The SRDF lists the floating root joint, as MoveIt's do; its 'standing' state wins."""
    bent = "".join(
        f'<joint name="{leg}_hip_joint" value="0"/><joint name="{leg}_thigh_joint" value="0.8"/>'
        f'<joint name="{leg}_calf_joint" value="-1.6"/>'
        for leg in ("FL", "FR", "RL", "RR")
    )
    write(tmp_path / "srdf/quad.srdf", STANDING_SRDF.format(straight="", bent=bent))
    _build(tmp_path, robots.quadruped())
    model, data = _scene(tmp_path)
    thigh = model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "FL_thigh_joint")]
    assert data.qpos[thigh] == pytest.approx(0.8)
    home = data.qpos[2]
    _hold(model, data, 5.0)
    assert _tilt(data) < 0.1
    assert data.qpos[2] > 0.9 * home
    assert {v["source"] for v in readiness(tmp_path)["home"]} == {"srdf"}
    assert _check(tmp_path)["stand"]["max_tilt"] < 0.2


def test_the_srdf_beside_a_urdf_floating_by_its_own_joint_gives_its_pose(tmp_path):
    """A URDF that floats by its own floating joint from `world` (robot.yaml's free_joint
    false) was not looked for an SRDF: the robot stood in a computed crouch instead."""
    bent = "".join(
        f'<joint name="{leg}_hip_joint" value="0"/><joint name="{leg}_thigh_joint" value="0.8"/>'
        f'<joint name="{leg}_calf_joint" value="-1.6"/>'
        for leg in ("FL", "FR", "RL", "RR")
    )
    write(tmp_path / "srdf/quad.srdf", STANDING_SRDF.format(straight="", bent=bent))
    floating = robots.quadruped().replace(
        '<robot name="quad">',
        '<robot name="quad"><link name="world"/><joint name="float" type="floating">'
        '<parent link="world"/><child link="trunk"/></joint>',
    )
    _build(tmp_path, floating, free_joint=False)
    assert {v["source"] for v in readiness(tmp_path)["home"]} == {"srdf"}
    model, data = _scene(tmp_path)
    thigh = model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "FL_thigh_joint")]
    assert data.qpos[thigh] == pytest.approx(0.8)


def test_an_srdf_state_naming_an_unknown_joint_is_one_line_with_the_file(tmp_path):
    write(
        tmp_path / "robot.srdf",
        '<robot name="q"><group_state name="home" group="all">'
        '<joint name="elbow" value="1"/></group_state></robot>',
    )
    with pytest.raises(BuildFailed) as failed:
        _build(tmp_path, robots.quadruped(), "self_collision: {srdf: robot.srdf}\n")
    message = str(failed.value)
    assert "robot.srdf" in message and "'elbow'" in message and "\n" not in message
    assert failed.value.exit_code == 4


def test_a_humanoid_stands_at_zero_with_weight_bearing_gains(tmp_path):
    _build(tmp_path, robots.humanoid())
    model, data = _scene(tmp_path)
    records = {r["joint"]: r for r in readiness(tmp_path)["actuators"]}
    ankle = records["left_ankle_pitch"]
    assert ankle["weight_bearing"]
    # The carried mass (all but one foot) at its height above the ankle, shared by two feet.
    mujoco.mj_forward(model, data)
    joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "left_ankle_pitch")
    foot = model.jnt_bodyid[joint]
    mass = model.body_subtreemass[0] - model.body_subtreemass[foot]
    com = (
        model.body_subtreemass[0] * data.subtree_com[0]
        - model.body_subtreemass[foot] * data.subtree_com[foot]
    ) / mass
    height = com[2] - data.xanchor[joint][2]
    assert ankle["kp"] == pytest.approx(MARGIN * mass * 9.81 * height / 2, rel=0.05)
    # Mirror-symmetric joints get the same gains.
    for name in ("hip_pitch", "hip_roll", "knee", "ankle_pitch", "ankle_roll"):
        left, right = records[f"left_{name}"], records[f"right_{name}"]
        assert (left["kp"], left["kv"]) == (right["kp"], right["kv"])
    _hold(model, data, 5.0)
    assert _tilt(data) < 0.1


def test_the_same_humanoid_falls_with_gains_from_its_own_inertia(tmp_path):
    """The counterfactual: ankles tuned by frequency alone let it tip, and the check says so
    in one line with what to write."""
    with pytest.raises(BuildFailed) as failed:
        _build(
            tmp_path,
            robots.humanoid(),
            'actuators: {rules: [{joints: ["*ankle*"], frequency: 10}]}\n',
        )
    assert failed.value.exit_code == 6
    assert "does not stand at home" in str(failed.value)
    assert "home:" in str(failed.value)


def test_a_continuous_arm_joint_holds_and_a_real_wheel_gets_a_velocity_servo(tmp_path):
    _build(tmp_path, robots.rover())
    records = {r["joint"]: r for r in readiness(tmp_path)["actuators"]}
    assert (records["left_wheel_joint"]["type"], records["left_wheel_joint"]["source"]) == (
        "velocity",
        "wheel",
    )
    assert records["right_wheel_joint"]["type"] == "velocity"
    assert records["shoulder"]["type"] == "dcmotor"  # a position servo with the URDF's line
    model, data = _scene(tmp_path)
    shoulder = model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "shoulder")]
    _hold(model, data, 1.0)
    assert abs(data.qpos[shoulder]) < 0.05  # the arm holds against gravity


def test_a_quadruped_with_continuous_leg_joints_keeps_standing(tmp_path):
    bent = "".join(
        f'<joint name="{leg}_thigh_joint" value="0.8"/><joint name="{leg}_calf_joint" value="-1.6"/>'
        for leg in ("FL", "FR", "RL", "RR")
    )
    write(tmp_path / "srdf/quad.srdf", STANDING_SRDF.format(straight="", bent=bent))
    _build(tmp_path, robots.quadruped(joint_type="continuous"))
    # position servos (with the URDF's speed line), no wheel among them
    assert {r["type"] for r in readiness(tmp_path)["actuators"]} == {"dcmotor"}
    model, data = _scene(tmp_path)
    home = data.qpos[2]
    _hold(model, data, 5.0)
    assert data.qpos[2] > 0.9 * home


def test_a_floating_joint_never_gets_an_actuator(tmp_path):
    """A drone whose URDF joins it to the world with a floating joint: no servo on it; it
    floats as options.free_joint makes a robot float, and the check holds it to the URDF."""
    write(tmp_path / "urdf/robot.urdf", robots.drone())
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: urdf/robot.urdf}\n")
    result = mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.nu == 0
    assert model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE


def test_a_floating_joint_with_an_origin_stands_on_the_floor_and_passes_the_check(tmp_path):
    """A URDF floating joint from `world` placed its child at the joint's origin, half a metre
    up: the build left it hanging there (free_joint: false, as init wrote) and the check
    compared the link with the free joint at zero, and failed a correct model."""
    urdf = """<robot name="f">
  <link name="world"/>
  <joint name="float" type="floating"><parent link="world"/><child link="torso"/>
    <origin xyz="0 0 0.5" rpy="0 0 0.7"/></joint>
  <link name="torso"><inertial><mass value="5"/>
    <inertia ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial>
    <collision><geometry><box size="0.3 0.2 0.1"/></geometry></collision></link>
</robot>
"""
    write(tmp_path / "f.urdf", urdf)
    assert run_cli("init", "f.urdf", cwd=tmp_path).code == 0
    assert "  free_joint: true\n" in (tmp_path / "robot.yaml").read_text()
    for setting in ("true", "false"):  # the URDF's own floating joint floats it either way
        manifest = tmp_path / "robot.yaml"
        manifest.write_text(
            re.sub(r"free_joint: \w+", f"free_joint: {setting}", manifest.read_text())
        )
        result = run_cli("build", "-q", cwd=tmp_path)
        assert result.code == 0, result.stderr
        model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "f.xml"))
        data = mujoco.MjData(model)
        mujoco.mj_resetDataKeyframe(model, data, 0)
        mujoco.mj_kinematics(model, data)
        assert data.qpos[2] == pytest.approx(0.05)  # its box on the floor, the yaw kept
        assert data.qpos[3] == pytest.approx(math.cos(0.35)) and data.qpos[6] == pytest.approx(
            math.sin(0.35)
        )


def test_a_ground_roots_geometry_is_not_what_stands_on_the_floor(tmp_path):
    """A root holding the robot by a floating joint stays in the world with its geometry (a
    slab below the floor here). The build stood the robot so the slab touched the floor and
    the check measured the floor gap from it: the robot hung 0.85 m up and the check failed."""
    slab = (
        '<link name="ground"><collision><origin xyz="0 0 -0.3"/><geometry>'
        '<box size="2 2 0.2"/></geometry></collision></link><joint name="float" '
        'type="floating"><parent link="ground"/><child link="base"/><origin xyz="0 0 0.5"/>'
        "</joint>"
    )
    result = build_two_link(tmp_path, urdf_extra=slab)
    (note,) = [w for w in result.warnings if "stands for the world" in w]
    assert "its geometry stays fixed there" in note
    model = load(result)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_kinematics(model, data)
    base = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "base")
    assert data.xpos[base][2] == pytest.approx(0.05)  # its 0.1 m box on the floor
    record = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert record["passes"], record["failures"]


def test_unknown_effort_and_velocity_are_not_limits(tmp_path):
    urdf = two_link_urdf().replace('effort="10" velocity="1"', 'effort="-1" velocity="-1"')
    result = _build(
        tmp_path, urdf, "actuators: {rules: [{joints: [hinge], type: velocity}]}\n", False
    )
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    hinge = actuator(model, "hinge")
    assert not model.actuator_ctrllimited[hinge]  # never the inverted [1, -1]
    assert not model.actuator_forcelimited[hinge]
    assert not model.jnt_actfrclimited[0]  # never a 1 N m limit
    assert any('effort="-1"' in w and "unknown" in w for w in result.warnings)
    assert any('velocity="-1"' in w for w in result.warnings)


def test_a_gripper_leader_is_sized_for_its_mimic_followers(tmp_path):
    """Four heavy fingers follow a light leader: the servo must hold them all."""
    # Plain servos: the URDF speed line's rotor inertia, the same with or without followers,
    # would blur the comparison of gains below.
    plain = "actuators: {speed_limits: false}\n"
    result = _build(tmp_path, robots.gripper(), plain, free_joint=False)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    lead = model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "lead")]
    home = data.qpos[lead]
    _hold(model, data, 1.0)
    assert abs(data.qpos[lead] - home) < 0.002
    record = readiness(tmp_path)["actuators"][0]
    alone = _build(tmp_path / "alone", robots.gripper(followers=0), plain, free_joint=False)
    assert alone.robot.exists()
    single = readiness(tmp_path / "alone")["actuators"][0]
    assert record["kp"] > 10 * single["kp"]


def test_the_speed_line_s_rotor_inertia_is_shared_with_the_mimic_followers(tmp_path):
    """The URDF speed line's armature went on the leader alone: a light mimic follower held by
    an equality to a leader of thousands of times its inertia chattered at tens of rad/s (an
    Inspire hand's fingers on a G1, 80 times their velocity limit). Each joint of the coupled
    motion now gets the same share, which adds up along it to what the servo was sized for."""
    result = _build(tmp_path, robots.gripper(followers=2, finger_mass=0.002), free_joint=False)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    names = ["lead", "finger0_joint", "finger1_joint"]
    shares = [
        float(
            model.dof_armature[
                model.jnt_dofadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)]
            ]
        )
        for name in names
    ]
    line = 40 / 0.2 * model.opt.timestep  # effort / velocity x time step (issue 33)
    assert shares == pytest.approx([line / 3] * 3, rel=1e-9)
    (record,) = readiness(tmp_path)["actuators"]
    assert record["armature"] == pytest.approx(line / 3, rel=1e-9)  # what the leader has


def test_a_forcerange_rule_sets_the_joint_limit_too(tmp_path):
    result = _build(
        tmp_path,
        two_link_urdf(),
        "actuators: {rules: [{joints: [hinge], forcerange: [-60, 60]}]}\n",
        free_joint=False,
    )
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert list(model.jnt_actfrcrange[0]) == [-60, 60]
    assert list(model.actuator_forcerange[0]) == [-60, 60]


def test_an_effort_below_the_gravity_load_names_both_numbers_and_the_fixes(tmp_path):
    heavy = two_link_urdf().replace('effort="10"', 'effort="0.5"')
    heavy = heavy.replace('rpy="0 0 0.3"/>', 'rpy="0 1.2 0.3"/>')  # the arm leans over
    arm = heavy.index('<link name="arm">') + len('<link name="arm">')
    heavy = heavy[:arm] + heavy[arm:].replace("<inertial>", '<inertial><origin xyz="0 0 0.25"/>', 1)
    with pytest.raises(BuildFailed) as failed:
        _build(tmp_path, heavy, "", free_joint=False)
    message = str(failed.value)
    assert failed.value.exit_code == 6
    assert "force limit is 0.5" in message and "forcerange" in message and "gravcomp" in message


def test_a_robot_without_any_mass_is_one_line_not_placeholders(tmp_path):
    import re

    bare = re.sub(r"<inertial>.*?</inertial>", "", two_link_urdf(), flags=re.S)
    with pytest.raises(BuildFailed) as failed:
        _build(tmp_path, bare, free_joint=False)
    assert failed.value.exit_code == 4
    assert "no link of the robot has a mass" in str(failed.value)
    assert "robot.urdf" in str(failed.value)


def test_a_quadruped_that_falls_at_zero_gets_a_computed_crouch_that_stands(tmp_path):
    """Feet 15 cm ahead of the hips, no SRDF, no home: it tips over at zero, so the build
    crouches each leg under its hip and keeps that only because it stands."""
    _build(tmp_path, robots.quadruped(foot_offset=0.15))
    record = readiness(tmp_path)
    assert record["home_from"].startswith("crouch")
    values = {h["joint"]: h for h in record["home"]}
    assert values["FL_thigh_joint"]["source"] == "computed"
    assert values["FL_thigh_joint"]["value"] > 0.3  # the thigh swings the foot back
    model, data = _scene(tmp_path)
    mujoco.mj_forward(model, data)
    foot = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "FL_calf")
    hip = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "FL_hip_joint")
    sphere = next(g for g in range(model.ngeom) if model.geom_bodyid[g] == foot)
    assert abs(data.geom_xpos[sphere][0] - data.xanchor[hip][0]) < 0.01  # under the hip
    _hold(model, data, 5.0)
    assert _tilt(data) < 0.1


def test_two_wheels_on_one_axle_need_a_controller_and_do_not_fail(tmp_path):
    """Wheels drawn as unlimited revolute joints are wheels; a tyre touches the floor at a
    point, so two on an axle span a line: the report says a controller is needed."""
    result = _build(tmp_path, robots.balancer())
    records = {r["joint"]: r for r in readiness(tmp_path)["actuators"]}
    assert records["left_wheel_joint"]["type"] == "velocity"
    check = _check(tmp_path)
    assert "a line" in check["needs_controller"]
    assert "stand test was not run" in " ".join(result.warnings)


def test_a_planar_base_joint_is_passive_and_said_so(tmp_path):
    result = _build(tmp_path, robots.planar_base(), free_joint=False)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.nu == 0
    assert readiness(tmp_path)["passive"] == ["base_joint_TX", "base_joint_TY", "base_joint_RZ"]
    assert any("planar joint 'base_joint'" in w for w in result.warnings)


def test_a_leader_is_sized_so_a_follower_with_a_large_multiplier_holds(tmp_path):
    """A follower moving 2.5 times its leader sags 2.5 times as far: the leader's servo is
    stiffened for the follower's sag, not its own."""
    urdf = robots.gripper(followers=1).replace('multiplier="1"', 'multiplier="2.5"')
    urdf = urdf.replace('upper="0.04" effort="40"', 'upper="0.1" effort="40"')
    _build(tmp_path, urdf, free_joint=False)
    model, data = _scene(tmp_path)
    follower = model.jnt_qposadr[
        mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "finger0_joint")
    ]
    home = data.qpos[follower]
    _hold(model, data, 1.0)
    assert abs(data.qpos[follower] - home) < 0.01 + 1e-4


def test_a_humanoid_takes_its_half_sitting_pose_from_an_srdf_naming_the_floating_joint(tmp_path):
    """MoveIt style: the root joint has a whole pose as its value and no virtual_joint says
    so; the state is still the robot's, and half_sitting is a standing pose."""
    bent = "".join(
        f'<joint name="{side}_hip_pitch" value="-0.3"/><joint name="{side}_knee" value="0.6"/>'
        f'<joint name="{side}_ankle_pitch" value="-0.3"/>'
        for side in ("left", "right")
    )
    write(
        tmp_path / "urdf/robot.srdf",
        '<robot name="biped"><group_state name="half_sitting" group="all">'
        f'<joint name="root_joint" value="0 0 0.9 0 0 0 1"/>{bent}</group_state></robot>',
    )
    _build(tmp_path, robots.humanoid())
    values = {h["joint"]: h for h in readiness(tmp_path)["home"]}
    assert (values["left_knee"]["value"], values["left_knee"]["source"]) == (0.6, "srdf")
    assert "half_sitting" in readiness(tmp_path)["home_from"]
    assert _check(tmp_path)["stand"]["max_tilt"] < 0.2


def test_a_part_world_holds_stays_put_beside_a_floating_joint(tmp_path):
    """The URDF's floating joint floats its robot; a table the same `world` holds by a fixed
    joint stayed static before and must not get a free joint of its own."""
    urdf = """<robot name="f">
  <link name="world"/>
  <joint name="float" type="floating"><parent link="world"/><child link="torso"/>
    <origin xyz="0 0 0.5"/></joint>
  <link name="torso"><inertial><mass value="5"/>
    <inertia ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial>
    <collision><geometry><box size="0.3 0.2 0.1"/></geometry></collision></link>
  <joint name="bolt" type="fixed"><parent link="world"/><child link="table"/>
    <origin xyz="2 0 0"/></joint>
  <link name="table"><inertial><mass value="20"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><box size="0.5 0.5 0.4"/></geometry></collision>
  </link>
</robot>
"""
    write(tmp_path / "f.urdf", urdf)
    write(tmp_path / "robot.yaml", "name: f\nsource: {urdf: f.urdf}\n")
    result = mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    free = [j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
    assert [model.body(model.jnt_bodyid[j]).name for j in free] == ["torso"]
