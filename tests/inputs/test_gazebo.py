"""A URDF's own top-level <sensor> elements: made from a Gazebo or ros2_control sensor of the
same name where there is one, else one warning per kind."""

from __future__ import annotations

from lxml import etree

from mjcfbuild.inputs.gazebo import read_gazebo_sensors, urdf_sensor_warnings
from tests.conftest import two_link_urdf

# As iCub writes them: each URDF sensor beside a Gazebo sensor of the same name, or not.
SENSORS = """
  <sensor name="arm_ft" type="force_torque"><parent joint="hinge"/></sensor>
  <gazebo reference="hinge"><sensor name="arm_ft" type="force_torque"/></gazebo>
  <sensor name="base_acc" type="accelerometer"><parent link="base"/></sensor>
  <sensor name="base_gyro" type="gyroscope"><parent link="base"/></sensor>
  <sensor name="arm_gyro" type="gyroscope"><parent link="arm"/></sensor>
  <sensor name="arm_imu" type="gyroscope"><parent link="arm"/></sensor>
"""


def test_urdf_sensors_without_a_counterpart_are_named_once_per_kind():
    root = etree.fromstring(two_link_urdf(SENSORS).encode())
    gazebo = read_gazebo_sensors(root, "robot.urdf")
    warnings = urdf_sensor_warnings(root, "robot.urdf", gazebo, {"arm_imu"})
    assert len(warnings) == 2
    accelerometer, gyroscope = warnings
    assert accelerometer.startswith(
        "robot.urdf:18: 1 URDF <sensor> element of kind accelerometer is not modelled: base_acc ("
    )
    assert gyroscope.startswith(
        "robot.urdf:19: 2 URDF <sensor> elements of kind gyroscope are not modelled: "
        "base_gyro, arm_gyro ("
    )
    assert "arm_ft" not in " ".join(warnings)


def test_no_urdf_sensors_no_warning():
    root = etree.fromstring(two_link_urdf().encode())
    assert urdf_sensor_warnings(root, "robot.urdf", [], set()) == []
