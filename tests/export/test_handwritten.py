"""export-urdf on a hand-written MJCF: an independent parser (yourdfpy) loads the URDF and its
meshes, and its forward kinematics match MuJoCo's at random configurations."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest
from lxml import etree

from tests.conftest import run_cli
from tests.export.handwritten import write_model

yourdfpy = pytest.importorskip("yourdfpy")


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    folder = tmp_path_factory.mktemp("handwritten")
    model_path = write_model(folder / "model")
    result = run_cli("export-urdf", str(model_path), "-o", str(folder / "out" / "robot.urdf"))
    assert result.code == 0, result.stderr
    assert "ball joint 'wrist_ball' became three revolute joints" in result.stderr
    return model_path, folder / "out" / "robot.urdf"


def quat_of_rotations(angles) -> np.ndarray:
    """The ball joint quaternion of turning about x, then the new y, then the new z."""
    quat = np.array([1.0, 0.0, 0.0, 0.0])
    for axis, angle in zip(np.eye(3), angles, strict=True):
        step = np.zeros(4)
        mujoco.mju_axisAngle2Quat(step, axis, angle)
        result = np.zeros(4)
        mujoco.mju_mulQuat(result, quat, step)
        quat = result
    return quat


def test_forward_kinematics_match_mujoco(exported):
    model_path, urdf_path = exported
    model = mujoco.MjModel.from_xml_path(str(model_path))
    data = mujoco.MjData(model)
    urdf = yourdfpy.URDF.load(str(urdf_path), load_meshes=True, build_scene_graph=True)
    assert urdf.base_link == "base"
    rng = np.random.default_rng(7)
    for _ in range(20):
        values = {}
        for name in urdf.actuated_joint_names:
            joint = urdf.joint_map[name]
            low, high = (
                (joint.limit.lower, joint.limit.upper)
                if joint.type != "continuous"
                else (-math.pi, math.pi)
            )
            values[name] = float(rng.uniform(low, high))
        urdf.update_cfg(values)
        for name in ("yaw", "pitch", "extend", "spin", "finger_a"):
            data.joint(name).qpos[0] = values[name]
        data.joint("finger_b").qpos[0] = values["finger_a"] + 0.001  # the coupling
        ball = [values[f"wrist_ball_{axis}"] for axis in "xyz"]
        data.joint("wrist_ball").qpos[:] = quat_of_rotations(ball)
        mujoco.mj_kinematics(model, data)
        base = np.eye(4)
        base[:3, :3] = data.body("base").xmat.reshape(3, 3)
        base[:3, 3] = data.body("base").xpos
        for body in ("arm", "slider", "wheel", "wrist", "finger_a", "finger_b"):
            expected = np.eye(4)
            expected[:3, :3] = data.body(body).xmat.reshape(3, 3)
            expected[:3, 3] = data.body(body).xpos
            expected = np.linalg.inv(base) @ expected
            actual = urdf.get_transform(body, "base")
            assert np.allclose(actual, expected, atol=1e-9), body
        tool = np.eye(4)
        tool[:3, :3] = data.site("tool").xmat.reshape(3, 3)
        tool[:3, 3] = data.site("tool").xpos
        assert np.allclose(
            urdf.get_transform("tool", "base"), np.linalg.inv(base) @ tool, atol=1e-9
        )


def test_geometry_and_joints(exported):
    _, urdf_path = exported
    root = etree.parse(str(urdf_path)).getroot()
    joints = {j.get("name"): j for j in root.iter("joint")}
    assert joints["spin"].get("type") == "continuous"  # the unlimited hinge
    assert joints["extend"].get("type") == "prismatic"
    assert joints["yaw"].find("child").get("link") == "arm_yaw"  # two joints: a chain
    assert joints["arm_joint"].get("type") == "fixed"
    mimic = joints["finger_b"].find("mimic")
    assert (mimic.get("joint"), mimic.get("multiplier"), mimic.get("offset")) == (
        "finger_a",
        "1",
        "0.001",
    )
    arm = root.find("link[@name='arm']")
    # capsules: a cylinder and two spheres, as visual (class visual) and collision (class collision)
    assert [g.tag for g in arm.find("visual").find("geometry")] == ["cylinder"]
    assert len(arm.findall("visual")) == 3 and len(arm.findall("collision")) == 3
    assert arm.find("collision/geometry/sphere").get("radius") == "0.035"
    slider = root.find("link[@name='slider']")
    visual_meshes = [m.get("filename") for m in slider.findall("visual/geometry/mesh")]
    assert visual_meshes == ["robot_meshes/part_9999a6ff.obj", "robot_meshes/part_e51a1aff.obj"]
    assert len(slider.findall("collision")) == 1  # the red copy is visual only
    colours = {m.get("name"): m.find("color").get("rgba") for m in root.findall("material")}
    assert colours["color_e51a1aff"] == "0.9 0.1 0.1 1"
    meshes = urdf_path.parent / "robot_meshes"
    assert "Kd 0.9 0.1 0.1" in (meshes / "part_e51a1aff.mtl").read_text()
    assert "Kd 0.6 0.6 0.65" in (meshes / "part_9999a6ff.mtl").read_text()
    assert (meshes / "part_e51a1aff.obj").read_text().startswith("mtllib part_e51a1aff.mtl\n")


def test_masses_and_inertia_match_mujoco(exported):
    model_path, urdf_path = exported
    model = mujoco.MjModel.from_xml_path(str(model_path))
    urdf = yourdfpy.URDF.load(str(urdf_path), load_meshes=False)
    for body in ("base", "arm", "slider", "wheel", "wrist", "finger_a", "finger_b"):
        inertial = urdf.link_map[body].inertial
        assert inertial.mass == pytest.approx(model.body(body).mass[0], rel=1e-9)
        moments = np.linalg.eigvalsh(inertial.inertia)
        assert moments == pytest.approx(sorted(model.body(body).inertia), rel=1e-9, abs=1e-15)
        assert inertial.origin[:3, 3] == pytest.approx(model.body(body).ipos, abs=1e-12)


def test_the_same_model_gives_the_same_bytes(exported, tmp_path):
    model_path, urdf_path = exported
    again = tmp_path / "robot.urdf"
    assert run_cli("export-urdf", str(model_path), "-o", str(again)).code == 0
    assert again.read_bytes() == urdf_path.read_bytes()
    for mesh in (urdf_path.parent / "robot_meshes").iterdir():
        assert (tmp_path / "robot_meshes" / mesh.name).read_bytes() == mesh.read_bytes()


def test_asset_prefix_and_no_sites(exported, tmp_path):
    model_path, _ = exported
    out = tmp_path / "robot.urdf"
    result = run_cli(
        "export-urdf",
        str(model_path),
        "-o",
        str(out),
        "--asset-prefix",
        "package://my_robot/meshes/",
        "--no-sites",
    )
    assert result.code == 0, result.stderr
    text = out.read_text()
    assert 'filename="package://my_robot/meshes/part_9999a6ff.obj"' in text
    assert '<link name="tool"/>' not in text


def test_unloadable_model_is_a_model_error(tmp_path):
    broken = tmp_path / "broken.xml"
    broken.write_text("<mujoco><worldbody><geom type='mesh' mesh='nope'/></worldbody></mujoco>")
    result = run_cli("export-urdf", str(broken), "-o", str(tmp_path / "r.urdf"))
    assert result.code == 5 and "broken.xml: MuJoCo cannot load the model" in result.stderr
    assert "Traceback" not in result.stderr and not (tmp_path / "r.urdf").exists()
