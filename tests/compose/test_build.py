"""The arm_gripper example: two descriptions built into one model, rules naming the gripper's
prefixed joints, the self-collision matrix and the check covering both parts, incremental
rebuilds per part, and bad attachments stopping the build before anything is written."""

from __future__ import annotations

import filecmp
import json

import mujoco
import pytest

import mjcfbuild
from mjcfbuild.errors import EXIT_INPUT, EXIT_MANIFEST, EXIT_OK
from tests.conftest import copy_example, run_cli, simple_manifest, two_link_urdf, write


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    folder = copy_example("arm_gripper", tmp_path_factory.mktemp("built"))
    result = mjcfbuild.build(folder / "robot.yaml", jobs=2)
    assert result.ok
    return folder, result


def test_the_model_holds_both_parts_with_the_gripper_prefixed(built):
    _, result = built
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    bodies = {model.body(i).name for i in range(model.nbody)}
    assert {"wrist_link", "gripper_left_jaw", "gripper_right_jaw"} <= bodies
    joint = model.joint("gripper_left_jaw_joint")
    assert tuple(joint.range) == (0.0, 0.025)  # the part's xacro args
    # The palm is fused into the wrist: tool0 (0.04 up, turned 90 degrees) + pos 0.06.
    site = model.site("gripper_palm")
    assert model.site_bodyid[site.id] == model.body("wrist_link").id
    assert list(model.site_pos[site.id]) == pytest.approx([0, 0, 0.1])
    assert model.neq == 2  # the arm's finger mimic and the gripper's jaw mimic


def _kp(model, actuator) -> float:
    """A position servo's kp: a <dcmotor>'s sits after its motor constants."""
    dcmotor = model.actuator_gaintype[actuator.id] == mujoco.mjtGain.mjGAIN_DCMOTOR
    return float(actuator.gainprm[4] if dcmotor else actuator.gainprm[0])


def test_actuator_rules_and_home_name_prefixed_joints(built):
    _, result = built
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    arm = model.actuator("elbow")
    jaw = model.actuator("gripper_left_jaw_joint")
    assert model.actuator_trnid[jaw.id][0] == model.joint("gripper_left_jaw_joint").id
    assert _kp(model, jaw) < _kp(model, arm)  # the rule's 5 Hz on a light jaw
    home = model.key("home")
    assert home.qpos[model.jnt_qposadr[model.joint("gripper_left_jaw_joint").id]] == 0.02
    assert home.qpos[model.jnt_qposadr[model.joint("elbow").id]] == 0.6
    names = {model.actuator(i).name for i in range(model.nu)}
    assert "gripper_right_jaw_joint" not in names  # a mimic follower


def test_self_collision_and_check_cover_the_pairs_and_links_across_parts(built):
    folder, _ = built
    state = folder / "mjcf" / ".mjcfbuild"
    pairs = json.loads((state / "self_collision.json").read_text())["pairs"]
    across = {
        (p["body1"], p["body2"])
        for p in pairs
        if p["body1"].startswith("gripper_") != p["body2"].startswith("gripper_")
    }
    assert ("forearm_link", "gripper_left_jaw") in across
    # wrist_link holds the palm: the jaws are its children, filtered by MuJoCo as adjacent.
    adjacent = [p for p in pairs if p["reason"] == "adjacent"]
    assert any({p["body1"], p["body2"]} == {"wrist_link", "gripper_left_jaw"} for p in adjacent)
    check = json.loads((state / "check.json").read_text())
    assert check["passes"] and check["kinematics"]["reference"] == "yourdfpy"
    assert check["kinematics"]["missing_links"] == []
    assert check["kinematics"]["max_position_error"] < 1e-9


def test_editing_the_gripper_rebuilds_the_gripper_and_the_assembly_only(tmp_path):
    folder = copy_example("arm_gripper", tmp_path)
    first = mjcfbuild.build(folder / "robot.yaml", jobs=2, check=False)
    assert {"expand", "expand:gripper_", "compose", "mesh:base", "mesh:palm"} <= set(first.ran)
    xacro = folder / "gripper" / "urdf" / "gripper.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('mass value="0.25"', 'mass value="0.3"'))
    second = mjcfbuild.build(folder / "robot.yaml", jobs=2, check=False)
    assert {"expand:gripper_", "compose", "plan", "assemble"} <= set(second.ran)
    assert not [name for name in second.ran if name.startswith("mesh:") or name == "expand"]
    assert mjcfbuild.build(folder / "robot.yaml", jobs=2, check=False).ran == []


def test_two_builds_in_different_folders_are_byte_identical(tmp_path):
    outputs = []
    for name, seed in (("one", "1"), ("elsewhere/two", "2")):
        folder = copy_example("arm_gripper", tmp_path / name)
        env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / f"cache-{seed}"), "PYTHONHASHSEED": seed}
        done = run_cli("build", "-q", "--no-check", cwd=folder, env=env)
        assert done.code == EXIT_OK, done.stderr
        outputs.append(folder / "mjcf")
    files = sorted(p.name for p in outputs[0].glob("*.xml"))
    assert files == ["arm_with_gripper.xml", "scene.xml"]
    _, mismatch, errors = filecmp.cmpfiles(*outputs, files, shallow=False)
    assert mismatch == [] and errors == []
    assert str(tmp_path).encode() not in (outputs[0] / files[0]).read_bytes()


@pytest.mark.parametrize(
    ("old", "new", "message", "line"),
    [
        ("to: tool0", "to: tool9", "'to' names link 'tool9', which is not a link", 16),
        ("prefix: gripper_", "prefix: upper_", None, None),
        (
            "xacro: gripper/urdf/gripper.urdf.xacro",
            "xacro: gripper/urdf/missing.xacro",
            "part file not found",
            14,
        ),
        ("euler: [0, 0, 0]", "quat: [0, 0, 0, 0]", "quat must not be zero", 13),
        ("euler: [0, 0, 0]", "euler: [0, 0, 0]\n    quat: [1, 0, 0, 0]", "not both", 13),
    ],
)
def test_bad_attachments_are_one_line_errors_and_write_nothing(tmp_path, old, new, message, line):
    folder = copy_example("arm_gripper", tmp_path)
    manifest = folder / "robot.yaml"
    text = manifest.read_text()
    if old == "prefix: gripper_":  # a part link 'arm_link' would become the arm's upper_arm_link
        xacro = folder / "gripper" / "urdf" / "gripper.urdf.xacro"
        xacro.write_text(xacro.read_text().replace('"palm"', '"arm_link"'))
        message, line = "link name 'upper_arm_link'", 17
    manifest.write_text(text.replace(old, new))
    done = run_cli("build", cwd=folder)
    # a missing part file is a missing input, as a missing source is
    assert done.code == (EXIT_INPUT if message == "part file not found" else EXIT_MANIFEST)
    error = [row for row in done.stderr.splitlines() if "error" in row]
    assert len(error) == 1 and message in error[0], done.stderr
    assert error[0].startswith(f"mjcfbuild: error: robot.yaml:{line}:"), error[0]
    assert not (folder / "mjcf" / "arm_with_gripper.xml").exists()
    assert "Traceback" not in done.stderr


# A part with a camera on its link and an IMU (Gazebo sensors), a <gazebo> plugin without a
# reference, and a URDF-level accelerometer no Gazebo sensor describes.
HAND = """<robot name="hand">
  <link name="palm"><inertial><mass value="0.2"/>
    <inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.05 0.05 0.02"/></geometry></collision></link>
  <gazebo reference="palm">
    <sensor name="palm_camera" type="camera"><pose>0 0 0.02 0 0 0</pose>
      <camera><horizontal_fov>1.2</horizontal_fov><image><width>64</width>
      <height>48</height></image></camera></sensor>
    <sensor name="palm_imu" type="imu"/>
  </gazebo>
  <gazebo><plugin name="hand_plugin" filename="libhand.so"/></gazebo>
  <sensor name="palm_acc" type="accelerometer"><parent link="palm"/></sensor>
</robot>
"""


def test_an_attached_parts_gazebo_sensors_are_built_and_its_urdf_sensors_named(tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "hand.urdf", HAND)
    simple_manifest(
        tmp_path,
        extra="attach:\n  - source: {urdf: hand.urdf}\n    to: arm\n    prefix: hand_\n",
    )
    result = run_cli("build", "-q", "--no-check", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "robot.xml"))
    assert model.cam_resolution[model.camera("hand_palm_camera").id].tolist() == [64, 48]
    sensors = {model.sensor(i).name for i in range(model.nsensor)}
    assert {"hand_palm_imu_quat", "hand_palm_imu_gyro", "hand_palm_imu_accel"} <= sensors
    warnings = json.loads((tmp_path / "mjcf" / "report" / "report.json").read_text())["warnings"]
    plugin = [w for w in warnings if "<gazebo> without a reference left out" in w]
    accelerometer = [w for w in warnings if "of kind accelerometer is not modelled" in w]
    assert len(plugin) == 1 and plugin[0].startswith("hand.urdf: ")
    assert len(accelerometer) == 1 and "hand_palm_acc" in accelerometer[0]
