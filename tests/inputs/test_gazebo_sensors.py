"""Gazebo sensors become their MJCF counterparts, named as mujoco_ros2_control looks them up,
on sites at their link and SDF <pose> (1e-9 from the URDF frame), written once where a
ros2_control sensor describes the same device."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys

import mujoco
import numpy as np
import pytest

import mjcfbuild
from mjcfbuild.errors import EXIT_INPUT
from mjcfbuild.inputs.gazebo_sensors import vertical_fov
from tests.conftest import INERTIA, run_cli, two_link_urdf, write
from tests.inputs.test_control_sensors import pose, rpy

# A link fixed below the arm (fused into its body) that carries the sensors.
MOUNT = f"""
  <link name="head">{INERTIA}</link>
  <joint name="head_mount" type="fixed"><parent link="arm"/><child link="head"/>
    <origin xyz="0.01 0.02 0.4" rpy="0.1 -0.2 0.3"/></joint>
"""
# Each sensor's <pose> in its link's frame (SDF: x y z roll pitch yaw).
POSES = {
    "body_imu": ((0.01, 0, 0.02), (0, 0, 0.5)),
    "wrist_ft": ((0, 0, 0.03), (0.2, 0, 0)),
    "compass": ((0, 0, 0), (0, 0, 0)),
    "front_camera": ((0.05, 0, 0.02), (0, 0.3, 0.1)),
    "depth_camera": ((0.05, 0.01, 0), (0, 0, -0.4)),
    "scan": ((0, 0, 0.1), (0, 0, 0.2)),
}


def gz_pose(name: str) -> str:
    xyz, angles = POSES[name]
    return f"<pose>{' '.join(map(str, (*xyz, *angles)))}</pose>"


GAZEBO = f"""
  <gazebo reference="head">
    <sensor name="body_imu" type="imu"><update_rate>200</update_rate>{gz_pose("body_imu")}
      <imu><angular_velocity><x><noise type="gaussian"><stddev>0.01</stddev></noise></x>
      </angular_velocity></imu></sensor>
    <sensor name="compass" type="magnetometer">{gz_pose("compass")}</sensor>
    <sensor name="front_camera" type="camera">{gz_pose("front_camera")}
      <camera><horizontal_fov>1.2</horizontal_fov><image><width>640</width>
      <height>480</height></image><clip><near>0.05</near><far>50</far></clip></camera>
      <update_rate>30</update_rate></sensor>
    <sensor name="depth_camera" type="depth">{gz_pose("depth_camera")}
      <camera><horizontal_fov>1.5</horizontal_fov><image><width>320</width>
      <height>180</height></image></camera></sensor>
    <sensor name="scan" type="gpu_lidar">{gz_pose("scan")}
      <lidar><scan><horizontal><samples>13</samples><min_angle>-0.6</min_angle>
      <max_angle>0.6</max_angle></horizontal></scan><range><min>0.1</min><max>12</max>
      </range></lidar></sensor>
    <sensor name="gps_1" type="gps"/>
    <sensor name="gps_2" type="navsat"/>
    <sensor name="gps_3" type="gps"/>
  </gazebo>
  <gazebo reference="head_mount">
    <sensor name="wrist_ft" type="force_torque">{gz_pose("wrist_ft")}</sensor>
  </gazebo>
  <gazebo reference="arm">
    <sensor name="bumper" type="contact"><contact><collision>arm_collision</collision>
    </contact></sensor>
  </gazebo>
"""
# The MJCF sensors and the Gazebo sensor whose site each is on.
EXPECTED = {
    "body_imu_quat": ("framequat", "body_imu"),
    "body_imu_gyro": ("gyro", "body_imu"),
    "body_imu_accel": ("accelerometer", "body_imu"),
    "wrist_ft_force": ("force", "wrist_ft"),
    "wrist_ft_torque": ("torque", "wrist_ft"),
    "compass": ("magnetometer", "compass"),
}
TYPES = {
    "framequat": mujoco.mjtSensor.mjSENS_FRAMEQUAT,
    "gyro": mujoco.mjtSensor.mjSENS_GYRO,
    "accelerometer": mujoco.mjtSensor.mjSENS_ACCELEROMETER,
    "force": mujoco.mjtSensor.mjSENS_FORCE,
    "torque": mujoco.mjtSensor.mjSENS_TORQUE,
    "magnetometer": mujoco.mjtSensor.mjSENS_MAGNETOMETER,
}


def head_frame(hinge: float) -> np.ndarray:
    """The URDF pose of link ``head`` in the world with the hinge (about y) at ``hinge``."""
    turn = np.eye(4)
    turn[:3, :3] = rpy(0, hinge, 0)
    return pose((0, 0, 0.1), (0, 0, 0.3)) @ turn @ pose((0.01, 0.02, 0.4), (0.1, -0.2, 0.3))


def sensor_frame(name: str, hinge: float) -> np.ndarray:
    return head_frame(hinge) @ pose(*POSES[name])


def build(folder, extra: str):
    write(folder / "robot.urdf", two_link_urdf(extra=MOUNT + extra))
    write(folder / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = mjcfbuild.build(folder / "robot.yaml")
    return mujoco.MjModel.from_xml_path(str(result.robot)), result


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    return build(tmp_path_factory.mktemp("gazebo"), GAZEBO)


def kinematics(model, hinge: float):
    data = mujoco.MjData(model)
    data.qpos[0] = hinge
    mujoco.mj_forward(model, data)  # cameras too
    return data


@pytest.mark.parametrize("hinge", [0.0, 0.7])
def test_imu_force_torque_and_magnetometer_sensors_sit_at_the_gazebo_pose(built, hinge):
    model, _ = built
    data = kinematics(model, hinge)
    for name, (tag, source) in EXPECTED.items():
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, name)
        assert index >= 0, f"no MJCF sensor {name}"
        assert model.sensor_type[index] == TYPES[tag], name
        assert model.sensor_objtype[index] == mujoco.mjtObj.mjOBJ_SITE, name
        site = model.sensor_objid[index]
        expected = sensor_frame(source, hinge)
        assert np.abs(data.site_xpos[site] - expected[:3, 3]).max() < 1e-9, name
        assert np.abs(data.site_xmat[site].reshape(3, 3) - expected[:3, :3]).max() < 1e-9, name


@pytest.mark.parametrize(
    ("name", "hfov", "size"),
    [("front_camera", 1.2, (640, 480)), ("depth_camera", 1.5, (320, 180))],
)
def test_cameras_look_along_the_gazebo_frames_x_with_its_z_up(built, name, hfov, size):
    model, _ = built
    data = kinematics(model, 0.4)
    camera = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, name)
    assert camera >= 0
    frame = sensor_frame(name, 0.4)
    axes = data.cam_xmat[camera].reshape(3, 3)
    # MuJoCo cameras look along -z with +y up.
    assert np.abs(-axes[:, 2] - frame[:3, 0]).max() < 1e-9
    assert np.abs(axes[:, 1] - frame[:3, 2]).max() < 1e-9
    assert np.abs(data.cam_xpos[camera] - frame[:3, 3]).max() < 1e-9
    width, height = size
    fovy = math.degrees(2 * math.atan(math.tan(hfov / 2) * height / width))
    assert model.cam_fovy[camera] == pytest.approx(fovy, abs=1e-6)
    assert tuple(model.cam_resolution[camera]) == size


def test_a_rendered_camera_sees_a_box_placed_on_the_gazebo_frames_x_axis(tmp_path):
    """A red box 1 m along the camera frame's +x fills the image centre."""
    box = f"""
  <link name="target"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4"
    ixy="0" ixz="0" iyz="0"/></inertial><visual><geometry><box size="0.2 0.2 0.2"/></geometry>
    <material name="red"><color rgba="1 0 0 1"/></material></visual></link>
  <joint name="target_mount" type="fixed"><parent link="base"/><child link="target"/>
    <origin xyz="1.2 0 0.5"/></joint>
  <link name="eye">{INERTIA}</link>
  <joint name="eye_mount" type="fixed"><parent link="base"/><child link="eye"/>
    <origin xyz="0.2 0 0.5"/></joint>
  <gazebo reference="eye"><sensor name="eye_cam" type="camera"><camera>
    <horizontal_fov>0.5</horizontal_fov><image><width>64</width><height>48</height></image>
  </camera></sensor></gazebo>
"""
    _, result = build(tmp_path, box)
    # Rendering needs MUJOCO_GL set before mujoco loads: a process of its own, as the
    # previews do.
    script = (
        "import json, sys, mujoco\n"
        "model = mujoco.MjModel.from_xml_path(sys.argv[1])\n"
        "data = mujoco.MjData(model)\n"
        "mujoco.mj_forward(model, data)\n"
        "with mujoco.Renderer(model, 48, 64) as renderer:\n"
        "    renderer.update_scene(data, camera='eye_cam')\n"
        "    image = renderer.render()\n"
        "print(json.dumps([image[24, 32].tolist(), image[2, 2].tolist()]))\n"
    )
    process = subprocess.run(
        [sys.executable, "-c", script, str(result.robot)],
        capture_output=True,
        text=True,
        env={**os.environ, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")},
        check=True,
    )
    centre, corner = json.loads(process.stdout.splitlines()[-1])

    def red(pixel):
        return pixel[0] > 100 and pixel[0] > 2 * max(pixel[1], pixel[2])

    assert red(centre) and not red(corner), (centre, corner)


def test_a_lidar_is_a_fan_of_rangefinders_from_the_samples_and_angles(built):
    model, _ = built
    data = kinematics(model, -0.3)
    frame = sensor_frame("scan", -0.3)
    rays = [
        i
        for i in range(model.nsensor)
        if model.sensor_type[i] == mujoco.mjtSensor.mjSENS_RANGEFINDER
    ]
    names = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SENSOR, i) for i in rays]
    assert len(rays) == 13 and all(n.startswith("scan-") for n in names), names
    for k, index in enumerate(rays):
        angle = -0.6 + k * 0.1
        site = model.sensor_objid[index]
        direction = frame[:3, :3] @ np.array([math.cos(angle), math.sin(angle), 0.0])
        ray = data.site_xmat[site].reshape(3, 3)[:, 2]  # rangefinders measure along +z
        assert np.abs(ray - direction).max() < 1e-9, k
        assert np.abs(data.site_xpos[site] - frame[:3, 3]).max() < 1e-9
        assert model.sensor_cutoff[index] == pytest.approx(12.0)


def test_a_contact_sensor_watches_its_links_body(built):
    model, _ = built
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, "bumper")
    assert model.sensor_type[index] == mujoco.mjtSensor.mjSENS_CONTACT
    arm = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "arm")
    assert model.sensor_objtype[index] == mujoco.mjtObj.mjOBJ_BODY
    assert model.sensor_objid[index] == arm


def test_kinds_mujoco_cannot_model_are_one_warning_line_per_kind(built):
    _, result = built
    gazebo = [w for w in result.warnings if "Gazebo sensor" in w]
    assert "2 Gazebo sensors of kind gps are not modelled: gps_1, gps_3" in gazebo
    assert "1 Gazebo sensor of kind navsat is not modelled: gps_2" in gazebo
    assert len(gazebo) == 2, gazebo


def test_noise_and_update_rates_go_to_the_check_report_not_the_warnings(built):
    import json

    _, result = built
    assert not any("update_rate" in w or "noise" in w for w in result.warnings)
    check = json.loads((result.robot.parent / ".mjcfbuild/check.json").read_text())
    listed = {entry["name"]: entry for entry in check["gazebo_sensors"]}
    assert listed["body_imu"]["not_modelled"] == ["update_rate 200 Hz", "noise"]
    assert "update_rate 30 Hz" in listed["front_camera"]["not_modelled"]
    assert listed["scan"]["not_modelled"] == ["range min 0.1 m"]
    assert listed["gps_1"]["modelled"] is False and listed["body_imu"]["modelled"] is True
    report = (result.robot.parent / "report/report.md").read_text()
    assert "| body_imu | imu | head | update_rate 200 Hz, noise |" in report
    assert "| gps_1 | gps | head | the sensor |" in report


CONTROL = """
  <ros2_control name="s" type="system">
    <hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>
    <sensor name="head_imu"><param name="mujoco_type">imu</param>
      <param name="frame_name">head</param></sensor>
    <sensor name="front_camera"><param name="frame_name">head</param>
      <param name="image_topic">/image</param></sensor>
  </ros2_control>
"""


def test_a_sensor_ros2_control_also_describes_is_written_once_under_its_name(tmp_path):
    model, _ = build(tmp_path, GAZEBO + CONTROL)
    sensor_names = {
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SENSOR, i) for i in range(model.nsensor)
    }
    assert {"head_imu_quat", "head_imu_gyro", "head_imu_accel"} <= sensor_names
    assert not any(name.startswith("body_imu") for name in sensor_names)
    gyros = [
        i for i in range(model.nsensor) if model.sensor_type[i] == mujoco.mjtSensor.mjSENS_GYRO
    ]
    assert len(gyros) == 1
    # Two Gazebo cameras on the link: ros2_control's camera sensor is matched by its name.
    cameras = {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_CAMERA, i) for i in range(model.ncam)}
    assert cameras == {"front_camera", "depth_camera"}


def test_a_lone_gazebo_camera_takes_the_name_ros2_control_expects(tmp_path):
    gazebo = '<gazebo reference="head"><sensor name="cam" type="camera"/></gazebo>'
    extra = gazebo + CONTROL.replace("front_camera", "head_camera")
    model, result = build(tmp_path, extra)
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "head_camera") >= 0
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "cam") < 0
    assert not any("head_camera" in w for w in result.warnings), result.warnings


def test_vertical_fov_of_a_square_image_is_the_horizontal_one():
    assert vertical_fov(math.radians(60), 100, 100) == pytest.approx(60.0)
    assert vertical_fov(math.radians(90), 200, 100) == pytest.approx(
        math.degrees(2 * math.atan(0.5))
    )


def test_a_gazebo_sensor_on_a_missing_link_is_one_line_with_the_urdf_line(tmp_path):
    sensor = '<sensor name="imu" type="imu"/>'
    block = f'<gazebo reference="nowhere">\n{sensor}\n</gazebo>'
    text = two_link_urdf(extra=block)
    write(tmp_path / "robot.urdf", text)
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_INPUT, result.stderr
    error = [line for line in result.stderr.splitlines() if "error" in line]
    assert len(error) == 1, result.stderr
    line = text.splitlines().index(sensor) + 1
    assert f"robot.urdf:{line}:" in error[0], error[0]
    assert "Gazebo sensor 'imu' is on 'nowhere', which is not a link" in error[0]
    assert "Traceback" not in result.stderr


def test_a_gazebo_sensor_on_a_misspelt_link_names_the_closest(tmp_path):
    """Issue 43: the closest link (or joint) is named."""
    write(
        tmp_path / "robot.urdf",
        two_link_urdf(extra='<gazebo reference="amr"><sensor name="imu1" type="imu"/></gazebo>'),
    )
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_INPUT, result.stderr
    assert (
        "Gazebo sensor 'imu1' is on 'amr', which is not a link (or joint) of the URDF; "
        "did you mean 'arm'?"
    ) in result.stderr


def test_a_force_torque_sensor_on_a_fused_link_is_warned_and_measures_the_weld_unfused(
    built, tmp_path
):
    _, result = built
    assert any(
        w.startswith("1 Gazebo force_torque or contact sensor on links fused")
        and "wrist_ft (on arm)" in w
        and "options.fuse_static: false" in w
        for w in result.warnings
    ), result.warnings
    # Kept as a body of its own, the sensor measures what holds the 1 kg head: its weight.
    write(tmp_path / "robot.urdf", two_link_urdf(extra=MOUNT + GAZEBO))
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\noptions: {fuse_static: false}\n",
    )
    unfused = mjcfbuild.build(tmp_path / "robot.yaml")
    assert not any("fused" in w for w in unfused.warnings)
    model = mujoco.MjModel.from_xml_path(str(unfused.robot))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, "wrist_ft_force")
    force = data.sensordata[model.sensor_adr[index] : model.sensor_adr[index] + 3]
    # (the arm starts to sag under gravity: the head accelerates a little). Fused, the sensor
    # would carry the arm too: twice that.
    assert np.linalg.norm(force) == pytest.approx(9.81, rel=0.01)


def test_two_gazebo_sensors_of_one_name_are_written_once_and_warned(tmp_path):
    twice = '<gazebo reference="head"><sensor name="imu" type="imu"/></gazebo>'
    model, result = build(tmp_path, twice + twice.replace("head", "arm"))
    gyros = [
        i for i in range(model.nsensor) if model.sensor_type[i] == mujoco.mjtSensor.mjSENS_GYRO
    ]
    assert len(gyros) == 1
    line = two_link_urdf(extra=MOUNT + twice + twice.replace("head", "arm")).splitlines()
    number = next(i for i, text in enumerate(line) if 'reference="arm"' in text) + 1
    assert any(
        w.startswith(f"robot.urdf:{number}: Gazebo sensor 'imu' has the name of the one at ")
        and w.endswith("so only that one is written; rename one")
        for w in result.warnings
    ), result.warnings


def test_a_lidar_of_hundreds_of_rays_is_said_to_be_most_of_each_step(tmp_path):
    """MuJoCo casts every rangefinder at each step: TIAGo Pro's 1,639 made a step 9 ms (0.07
    without). A lidar of 13 rays says nothing; one of 400 says what it costs and the knob."""
    _, built = build(tmp_path / "small", GAZEBO)
    assert not any("rangefinders" in warning for warning in built.warnings)
    many = GAZEBO.replace("<samples>13</samples>", "<samples>400</samples>")
    model, result = build(tmp_path / "many", many)
    assert model.nsensor >= 400
    assert any(
        warning.startswith("the model's 400 rangefinders (scan) are cast at every simulation step")
        and "<horizontal><samples>" in warning
        for warning in result.warnings
    ), result.warnings
