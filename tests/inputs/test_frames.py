"""Camera and lidar frames, computed by hand for rotated and offset links, against MuJoCo."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjcfbuild.inputs.frames import ray_count, rays_short_of_max
from tests.conftest import INERTIA, write

URDF = """<robot name="r">
  <link name="base">{inertia}</link>
  <link name="arm">{inertia}</link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0.1 0.2 0.3" rpy="0.4 -0.3 0.9"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <link name="sensor"/>
  <joint name="s" type="fixed"><parent link="arm"/><child link="sensor"/>
    <origin xyz="0.05 -0.02 0.4" rpy="{rpy}"/></joint>
</robot>"""


def rpy_matrix(roll, pitch, yaw):
    def rx(a):
        return np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])

    def ry(a):
        return np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])

    def rz(a):
        return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])

    return rz(yaw) @ ry(pitch) @ rx(roll)


def sensor_frame(q, rpy):
    """The sensor link's world pose, by hand, with joint angle ``q``."""
    r_joint = rpy_matrix(0.4, -0.3, 0.9)
    r_arm = r_joint @ rpy_matrix(0, 0, q)
    position = np.array([0.1, 0.2, 0.3]) + r_arm @ np.array([0.05, -0.02, 0.4])
    return position, r_arm @ rpy_matrix(*rpy)


def build(tmp_path, rpy, manifest_inputs):
    import mjcfbuild

    write(tmp_path / "robot.urdf", URDF.format(inertia=INERTIA, rpy=" ".join(map(str, rpy))))
    write(
        tmp_path / "robot.yaml",
        f"name: r\nsource: {{urdf: robot.urdf}}\nmujoco_inputs:\n{manifest_inputs}",
    )
    return mujoco.MjModel.from_xml_path(str(mjcfbuild.build(tmp_path / "robot.yaml").robot))


@pytest.mark.parametrize("rpy", [(0, 0, 0), (-math.pi / 2, 0, -math.pi / 2), (0.7, 0.2, -1.3)])
def test_camera_looks_along_the_optical_z_with_image_up_along_minus_y(tmp_path, rpy):
    model = build(tmp_path, rpy, "  cameras: [{name: cam, link: sensor}]\n")
    data = mujoco.MjData(model)
    for q in (0.0, 0.8):
        data.qpos[0] = q
        mujoco.mj_kinematics(model, data)
        mujoco.mj_camlight(model, data)
        position, rotation = sensor_frame(q, rpy)
        camera = data.cam_xmat[0].reshape(3, 3)
        assert np.allclose(data.cam_xpos[0], position, atol=1e-12)
        assert np.allclose(-camera[:, 2], rotation[:, 2], atol=1e-12)  # looks along optical +z
        assert np.allclose(camera[:, 1], -rotation[:, 1], atol=1e-12)  # image up is optical -y
        assert np.allclose(camera[:, 0], rotation[:, 0], atol=1e-12)  # image right is optical +x


@pytest.mark.parametrize("rpy", [(0, 0, 0), (0.2, -0.4, 2.5)])
def test_lidar_rays_sweep_counterclockwise_about_the_link_z(tmp_path, rpy):
    inputs = "  lidars: [{sensor_name: ray, link: sensor, min_angle: -1.0, max_angle: 0.5, angle_increment: 0.25}]\n"
    model = build(tmp_path, rpy, inputs)
    data = mujoco.MjData(model)
    data.qpos[0] = -0.6
    mujoco.mj_kinematics(model, data)
    position, rotation = sensor_frame(-0.6, rpy)
    assert ray_count(-1.0, 0.5, 0.25) == 7
    for index in range(7):
        site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, f"ray-{index}")
        angle = -1.0 + 0.25 * index
        expected = rotation @ np.array([math.cos(angle), math.sin(angle), 0.0])
        assert np.allclose(data.site_xmat[site].reshape(3, 3)[:, 2], expected, atol=1e-12)
        assert np.allclose(data.site_xpos[site], position, atol=1e-12)


@pytest.mark.parametrize(
    ("low", "high", "step", "count", "short"),
    [
        # mujoco_ros2_control (and the reference converter) count int((max - min) / step) + 1
        # in doubles: 0.6 / 0.025 is 23.999999999999996, so 24 rays, the one at 0.3 left out.
        (-0.3, 0.3, 0.025, 24, True),
        (0, 1.57, 0.025, 63, False),
        (0, 0, 0.1, 1, False),
        (-math.pi, math.pi, math.pi / 180, 361, False),
        (-0.3, 0.3000001, 0.025, 25, False),
    ],
)
def test_ray_count_is_the_runtimes(low, high, step, count, short):
    assert ray_count(low, high, step) == count == int((high - low) / step) + 1
    assert rays_short_of_max(low, high, step) is short
