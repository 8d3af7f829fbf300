"""ros2_control: cameras and lidars matched to sensors, actuators and a home keyframe on request."""

from __future__ import annotations

import mujoco

import mjcfbuild
from tests.conftest import two_link_urdf, write

CONTROL = """<ros2_control name="sim" type="system">
  <joint name="hinge">
    <command_interface name="position"/><command_interface name="velocity"/>
    <state_interface name="position"><param name="initial_value">0.5</param></state_interface>
  </joint>
  <sensor name="front_camera"><param name="image_topic">/img</param></sensor>
</ros2_control>"""


def build(tmp_path, manifest_extra: str, control: str = CONTROL):
    write(tmp_path / "robot.urdf", two_link_urdf(extra=control))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + manifest_extra)
    return mjcfbuild.build(tmp_path / "robot.yaml")


def test_cameras_and_sensors_without_partners_are_warned_both_ways(tmp_path):
    result = build(tmp_path, "mujoco_inputs:\n  cameras: [{name: wrist_camera, link: arm}]\n")
    assert any(
        "camera 'wrist_camera' has no ros2_control <sensor name='wrist_camera'> "
        "(ros2_control sensors: front_camera)" in w
        for w in result.warnings
    )
    assert any(
        "ros2_control camera sensor 'front_camera' has no MuJoCo camera of its name" in w
        for w in result.warnings
    )


def test_actuators_from_command_interfaces_and_a_home_keyframe(tmp_path):
    result = build(
        tmp_path,
        "ros2_control:\n  actuators: true\n  home_keyframe: true\n"
        "  position: {kp: 50, dampratio: 0.7}\n  joints: {hinge: {kv: 3}}\n",
    )
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    position = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, "hinge_position")
    velocity = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, "hinge_velocity")
    assert model.actuator_gainprm[position][0] == 50
    assert list(model.actuator_ctrlrange[position]) == [-1.5, 1.5]
    assert model.actuator_gainprm[velocity][0] == 3
    assert list(model.actuator_ctrlrange[velocity]) == [-1, 1]
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    assert model.key_qpos[home][0] == 0.5


def test_inputs_that_drive_a_joint_keep_it(tmp_path):
    result = build(
        tmp_path,
        "ros2_control: {actuators: true}\nmujoco_inputs:\n"
        '  raw: \'<actuator><motor name="mine" joint="hinge"/></actuator>\'\n',
    )
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.nu == 1
    assert any("already has an actuator" in w for w in result.warnings)
