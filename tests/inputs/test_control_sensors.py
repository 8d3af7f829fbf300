"""The MJCF sensors mujoco_ros2_control reads a <ros2_control> <sensor> from are written, named
as the runtime looks them up, on sites at the sensor's frame (1e-9 from the URDF's)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

import mjcfbuild
from mjcfbuild.errors import EXIT_INPUT
from tests.conftest import INERTIA, run_cli, two_link_urdf, write

# Two links fixed below the arm (fused into its body), each at an origin of its own.
FRAMES = f"""
  <link name="imu_link">{INERTIA}</link>
  <joint name="imu_mount" type="fixed"><parent link="arm"/><child link="imu_link"/>
    <origin xyz="0.01 0.02 0.3" rpy="0.1 0.2 0.3"/></joint>
  <link name="ft_link">{INERTIA}</link>
  <joint name="ft_mount" type="fixed"><parent link="arm"/><child link="ft_link"/>
    <origin xyz="0 0 0.5" rpy="3.14159 0 0.5"/></joint>
"""
# The runtime reads the suffixes from the <hardware> of the sensor's block.
SENSORS = """
  <ros2_control name="defaults" type="system">
    <hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>
    <sensor name="imu_link"><param name="mujoco_type">imu</param></sensor>
    <sensor name="tool_pose"><param name="mujoco_type">pose</param>
      <param name="frame_name">ft_link</param></sensor>
    <sensor name="mag"><param name="mujoco_type">magnetometer</param>
      <param name="mujoco_sensor_name">compass</param><param name="frame_name">imu_link</param></sensor>
  </ros2_control>
  <ros2_control name="custom" type="system">
    <hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin>
      <param name="force_mjcf_suffix">_f</param><param name="torque_mjcf_suffix">_t</param>
      <param name="orientation_mjcf_suffix">_orientation</param>
    </hardware>
    <sensor name="wrist_ft"><param name="mujoco_type">fts</param>
      <param name="frame_name">ft_link</param></sensor>
    <sensor name="imu2"><param name="mujoco_type">imu</param>
      <param name="mujoco_sensor_name">body_imu</param><param name="frame_name">imu_link</param></sensor>
  </ros2_control>
"""
EXPECTED = {
    "imu_link_quat": ("framequat", "imu_link"),
    "imu_link_gyro": ("gyro", "imu_link"),
    "imu_link_accel": ("accelerometer", "imu_link"),
    "tool_pose_pos": ("framepos", "ft_link"),
    "tool_pose_quat": ("framequat", "ft_link"),
    "compass": ("magnetometer", "imu_link"),
    "wrist_ft_f": ("force", "ft_link"),
    "wrist_ft_t": ("torque", "ft_link"),
    "body_imu_orientation": ("framequat", "imu_link"),
    "body_imu_gyro": ("gyro", "imu_link"),
    "body_imu_accel": ("accelerometer", "imu_link"),
}
TYPES = {
    "framequat": mujoco.mjtSensor.mjSENS_FRAMEQUAT,
    "framepos": mujoco.mjtSensor.mjSENS_FRAMEPOS,
    "gyro": mujoco.mjtSensor.mjSENS_GYRO,
    "accelerometer": mujoco.mjtSensor.mjSENS_ACCELEROMETER,
    "force": mujoco.mjtSensor.mjSENS_FORCE,
    "torque": mujoco.mjtSensor.mjSENS_TORQUE,
    "magnetometer": mujoco.mjtSensor.mjSENS_MAGNETOMETER,
}


def rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF's fixed-axis roll, pitch, yaw: Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr, cp, sp, cy, sy = (f(a) for a in (roll, pitch, yaw) for f in (math.cos, math.sin))
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def pose(xyz, angles) -> np.ndarray:
    transform = np.eye(4)
    transform[:3, :3], transform[:3, 3] = rpy(*angles), xyz
    return transform


def urdf_frame(link: str, hinge: float) -> np.ndarray:
    """The URDF pose of ``link`` in the world with the hinge (about y) at ``hinge``."""
    turn = pose((0, 0, 0), (0, 0, 0))
    turn[:3, :3] = rpy(0, hinge, 0)
    arm = pose((0, 0, 0.1), (0, 0, 0.3)) @ turn
    mounts = {
        "imu_link": ((0.01, 0.02, 0.3), (0.1, 0.2, 0.3)),
        "ft_link": ((0, 0, 0.5), (3.14159, 0, 0.5)),
    }
    return arm @ pose(*mounts[link])


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sensors")
    write(folder / "robot.urdf", two_link_urdf(extra=FRAMES + SENSORS))
    write(folder / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = mjcfbuild.build(folder / "robot.yaml")
    return mujoco.MjModel.from_xml_path(str(result.robot)), folder


def test_every_sensor_the_runtime_looks_up_exists_with_its_type_on_a_site(built):
    model, _ = built
    for name, (tag, _) in EXPECTED.items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, name)
        assert index >= 0, f"no MJCF sensor {name}"
        assert model.sensor_type[index] == TYPES[tag], name
        assert model.sensor_objtype[index] == mujoco.mjtObj.mjOBJ_SITE, name


@pytest.mark.parametrize("hinge", [0.0, 0.7, -1.2])
def test_each_sensor_site_is_at_its_urdf_frame(built, hinge):
    model, _ = built
    data = mujoco.MjData(model)
    data.qpos[0] = hinge
    mujoco.mj_kinematics(model, data)
    for name, (_, frame) in EXPECTED.items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, name)
        site = model.sensor_objid[index]
        expected = urdf_frame(frame, hinge)
        assert np.abs(data.site_xpos[site] - expected[:3, 3]).max() < 1e-9, name
        assert np.abs(data.site_xmat[site].reshape(3, 3) - expected[:3, :3]).max() < 1e-9, name


def test_the_check_finds_every_sensor(built):
    import json

    _, folder = built
    check = json.loads((folder / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"], check["failures"]
    found = {m["name"]: m for s in check["mujoco_ros2_control"]["sensors"] for m in s["mjcf"]}
    assert set(found) == set(EXPECTED) and all(m["found"] and m["site"] for m in found.values())


def test_sensors_the_user_wrote_are_kept_as_written(tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf(extra=FRAMES + SENSORS))
    raw = '<sensor><framequat name="imu_link_quat" objtype="body" objname="arm"/></sensor>'
    write(
        tmp_path / "robot.yaml",
        f"name: r\nsource: {{urdf: robot.urdf}}\nmujoco_inputs:\n  raw: '{raw}'\n",
    )
    result = mjcfbuild.build(tmp_path / "robot.yaml")
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, "imu_link_quat")
    assert model.sensor_objtype[index] == mujoco.mjtObj.mjOBJ_BODY
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, "imu_link_gyro") >= 0


@pytest.mark.parametrize(
    ("sensor", "message"),
    [
        (
            '<sensor name="imu"><param name="mujoco_type">gps</param></sensor>',
            "ros2_control sensor 'imu' has mujoco_type 'gps', which mujoco_ros2_control does not know",
        ),
        (
            '<sensor name="imu"><param name="mujoco_type">imu</param></sensor>',
            "ros2_control sensor 'imu': its name 'imu' is not a link of the URDF",
        ),
        (
            '<sensor name="imu"><param name="mujoco_type">imu</param><param name="frame_name">nope</param></sensor>',
            "ros2_control sensor 'imu': its frame_name 'nope' is not a link of the URDF",
        ),
    ],
)
def test_a_sensor_the_build_cannot_place_is_one_line_with_the_urdf_line(tmp_path, sensor, message):
    block = f'<ros2_control name="s" type="system">\n{sensor}\n</ros2_control>'
    write(tmp_path / "robot.urdf", two_link_urdf(extra=block))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_INPUT, result.stderr
    error = [line for line in result.stderr.splitlines() if "error" in line]
    assert len(error) == 1 and message in error[0]
    line = two_link_urdf(extra=block).splitlines().index(sensor) + 1
    assert f"robot.urdf:{line}:" in error[0], error[0]
    assert "Traceback" not in result.stderr
