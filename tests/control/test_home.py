"""The home keyframe: from robot.yaml, ros2_control or zero; floating robots on the floor."""

from __future__ import annotations

import mujoco
import pytest

import mjcfbuild
from tests.conftest import INERTIA, write
from tests.control.helpers import build_two_link, load, readiness


def _home(model):
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    assert key >= 0
    return model.key_qpos[key], model.key_ctrl[key]


def test_home_from_robot_yaml_sets_qpos_and_the_ctrl_that_holds_it(tmp_path):
    model = load(build_two_link(tmp_path, "home: {'hin*': 0.7}\n"))
    qpos, ctrl = _home(model)
    assert qpos[0] == 0.7
    assert ctrl[0] == 0.7  # a position servo aims at home
    assert readiness(tmp_path)["home"][0]["source"] == "robot.yaml"


def test_home_from_ros2_control_initial_value(tmp_path):
    control = """<ros2_control name="s" type="system"><joint name="hinge">
      <command_interface name="position"/>
      <state_interface name="position"><param name="initial_value">-0.4</param></state_interface>
      </joint></ros2_control>"""
    model = load(build_two_link(tmp_path, urdf_extra=control))
    assert _home(model)[0][0] == -0.4
    assert readiness(tmp_path)["home"][0]["source"] == "ros2_control"


def test_zero_is_clipped_into_the_joint_range(tmp_path):
    write(tmp_path / "robot.urdf", _urdf(lower=0.2, upper=1.0))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    model = mujoco.MjModel.from_xml_path(str(mjcfbuild.build(tmp_path / "robot.yaml").robot))
    assert _home(model)[0][0] == 0.2


def test_mimic_followers_sit_where_their_equality_puts_them(tmp_path):
    write(tmp_path / "robot.urdf", _urdf(mimic=True))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\nhome: {hinge: 0.5}\n")
    model = mujoco.MjModel.from_xml_path(str(mjcfbuild.build(tmp_path / "robot.yaml").robot))
    qpos, _ = _home(model)
    assert list(qpos) == [0.5, pytest.approx(2 * 0.5 + 0.1)]
    assert model.nu == 1  # the follower has no actuator of its own


def test_motor_ctrl_at_home_pushes_against_gravity(tmp_path):
    write(tmp_path / "robot.urdf", _urdf(arm_com=0.3))
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\nhome: {hinge: 0.8}\nactuators: {default: motor}\n",
    )
    model = mujoco.MjModel.from_xml_path(str(mjcfbuild.build(tmp_path / "robot.yaml").robot))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    assert data.ctrl[0] == pytest.approx(data.qfrc_bias[0], rel=1e-9)
    assert abs(data.ctrl[0]) > 1  # 1 kg, 0.3 m out, tilted 0.8 rad
    for _ in range(500):
        mujoco.mj_step(model, data)
    assert abs(data.qpos[0] - 0.8) < 0.01


def test_a_floating_robot_stands_on_the_floor_and_qpos0_agrees(tmp_path):
    result = build_two_link(tmp_path, "options: {free_joint: true}\n")
    model = load(result)
    qpos, _ = _home(model)
    assert qpos[2] == pytest.approx(model.qpos0[2], abs=1e-12)
    # The base box is 0.1 m tall around the base frame: it is raised by half that.
    assert qpos[2] == pytest.approx(0.05, abs=1e-9)
    assert readiness(tmp_path)["base_height"] == pytest.approx(0.05, abs=1e-9)


def test_a_massless_floating_root_is_repaired_and_reported(tmp_path):
    write(tmp_path / "robot.urdf", _urdf(massless_root=True))
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\n",
    )
    # No check: the repaired root is so light that the hinge's servo spins it past the speed
    # bound (check.speeds) and the robot does not stand; the repair is this test's subject.
    result = mjcfbuild.build(tmp_path / "robot.yaml", check=False)
    assert any("floating root without mass" in w for w in result.warnings), result.warnings


def _urdf(lower=-1.5, upper=1.5, mimic=False, massless_root=False, arm_com=0.0) -> str:
    arm_inertia = INERTIA.replace("<mass", f'<origin xyz="0 0 {arm_com}"/><mass')
    follower = (
        """<link name="tip">{i}<collision><geometry><sphere radius="0.01"/></geometry></collision></link>
        <joint name="follower" type="revolute"><parent link="arm"/><child link="tip"/>
        <origin xyz="0 0 0.6"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
        <mimic joint="hinge" multiplier="2" offset="0.1"/></joint>""".replace("{i}", INERTIA)
        if mimic
        else ""
    )
    return f"""<robot name="r">
  <link name="root">{"" if massless_root else INERTIA}
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="arm">{arm_inertia}
    <collision><origin xyz="0 0 0.3"/><geometry><cylinder radius="0.03" length="0.4"/></geometry></collision></link>
  <joint name="hinge" type="revolute"><parent link="root"/><child link="arm"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="{lower}" upper="{upper}" effort="10" velocity="1"/></joint>
  {follower}
</robot>"""
