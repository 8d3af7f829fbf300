"""ros2_control: cameras and lidars matched to their sensors (actuators: tests/control)."""

from __future__ import annotations

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
