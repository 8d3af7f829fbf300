"""COLLADA up axis decided per file by its links' evidence: a file tagged Y-up that holds Y-up
data is turned, one tagged Y-up that holds Z-up data is kept; robot.yaml can force either; the
report says which files were turned and why."""

from __future__ import annotations

import json

import mujoco
import numpy as np
import pytest

import mjcfbuild
from mjcfbuild.meshes.upaxis import MeshUse, decide, read_up_axis
from mjcfbuild.urdf.mesh_uses import mesh_uses
from mjcfbuild.urdf.parse import parse_urdf
from tests.conftest import simple_manifest, write

# The upper arm hangs from its shoulder: 0.4 m long along -z, 6 cm by 10 cm across.
LOW = np.array([-0.03, -0.05, -0.4])
HIGH = np.array([0.03, 0.05, 0.0])


def box_triangles(low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A box's corners and 12 outward triangles."""
    corners = np.array(
        [[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1]) for z in (low[2], high[2])]
    )
    faces = np.array(
        [
            [0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
            [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3],
        ]
    )  # fmt: skip
    return corners, faces


def as_y_up(points: np.ndarray) -> np.ndarray:
    """Z-up coordinates written as a Y-up exporter writes them (up is +y, forward is +z)."""
    return np.stack([points[:, 0], points[:, 2], -points[:, 1]], axis=1)


def dae_text(vertices: np.ndarray, faces: np.ndarray, up: str) -> str:
    positions = " ".join(f"{v:.6g}" for v in vertices.ravel())
    indices = " ".join(str(i) for i in faces.ravel())
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1"/><up_axis>{up}</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="{vertices.size}">{positions}</float_array>
      <technique_common><accessor source="#pa" count="{len(vertices)}" stride="3"/>
      </technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="{len(faces)}"><input semantic="VERTEX" source="#v" offset="0"/>
      <p>{indices}</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"""


INERTIA = (
    '<inertial><origin xyz="0 0 -0.2"/><mass value="1"/>'
    '<inertia ixx="0.01" iyy="0.01" izz="0.002" ixy="0" ixz="0" iyz="0"/></inertial>'
)
ARM_BOX = (
    '<collision><origin xyz="0 0 -0.2"/><geometry><box size="0.06 0.1 0.4"/></geometry></collision>'
)


def urdf() -> str:
    """Two hanging links, each drawn by its own DAE file and colliding with an authored box."""
    return f"""<?xml version="1.0" encoding="utf-8"?>
<robot name="hanging">
  <link name="base"><inertial><mass value="2"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper">{INERTIA}
    <visual><geometry><mesh filename="meshes/upper.dae"/></geometry></visual>{ARM_BOX}</link>
  <link name="lower">{INERTIA}
    <visual><geometry><mesh filename="meshes/lower.dae"/></geometry></visual>{ARM_BOX}</link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 -0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="50" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 -0.4"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="50" velocity="1"/></joint>
</robot>
"""


@pytest.fixture
def robot_folder(tmp_path):
    """``upper.dae``: tagged Y-up, holding Y-up data; ``lower.dae``: tagged Y-up, Z-up data."""
    corners, faces = box_triangles(LOW, HIGH)
    write(tmp_path / "meshes" / "upper.dae", dae_text(as_y_up(corners), faces, "Y_UP"))
    write(tmp_path / "meshes" / "lower.dae", dae_text(corners, faces, "Y_UP"))
    write(tmp_path / "robot.urdf", urdf())
    return tmp_path


def visual_extent(model: mujoco.MjModel, body: str) -> np.ndarray:
    """The extent along x, y, z (in the body's frame) of the body's visual mesh."""
    from mjcfbuild.check.plausibility import _geom

    body_id = model.body(body).id
    for index in range(model.ngeom):
        if model.geom_bodyid[index] == body_id and model.geom_contype[index] == 0:
            points = _geom(model, index).points
            return points.max(axis=0) - points.min(axis=0)
    raise AssertionError(f"no visual geom in {body}")


def test_y_up_data_is_turned_and_z_up_data_tagged_y_up_is_kept(robot_folder):
    manifest = simple_manifest(robot_folder)
    result = mjcfbuild.build(manifest, jobs=1)
    assert result.ok, result
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    for body in ("upper", "lower"):  # both hang along z, as their links do
        assert visual_extent(model, body) == pytest.approx([0.06, 0.1, 0.4], abs=1e-6)
    report = json.loads((robot_folder / "mjcf" / "report" / "report.json").read_text())
    rows = {row["mesh"]: row for row in report["up_axis"]}
    assert rows["upper"]["turned"] and rows["upper"]["tag"] == "Y_UP"
    assert "link 'upper' fits it as tagged" in rows["upper"]["reason"]
    assert not rows["lower"]["turned"]
    assert "kept as written (its data is Z-up)" in rows["lower"]["reason"]
    page = (robot_folder / "mjcf" / "report" / "report.md").read_text()
    assert "COLLADA up axis: 1 of 2 DAE files tagged other than Z-up were turned." in page
    assert report["check"]["plausibility"]["findings"] == []
    # Nothing changed: nothing reruns.
    assert mjcfbuild.build(manifest, jobs=1).ran == []


def test_robot_yaml_forces_a_choice_per_file_and_the_check_names_the_cause(robot_folder):
    manifest = simple_manifest(
        robot_folder, extra="meshes:\n  collada_up_axis_files:\n    upper.dae: ignore\n"
    )
    result = mjcfbuild.build(manifest, jobs=1)
    assert result.ok, result  # a misplaced mesh is a warning, not a failure
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert visual_extent(model, "upper") == pytest.approx([0.06, 0.4, 0.1], abs=1e-6)
    check = json.loads((robot_folder / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    (finding,) = check["plausibility"]["findings"]
    assert finding["body"] == "upper" and finding["cause"] == "up axis"
    assert not finding["fails"]
    assert any("body 'upper'" in w and "up axis" in w for w in result.warnings)
    report = json.loads((robot_folder / "mjcf" / "report" / "report.json").read_text())
    rows = {row["mesh"]: row for row in report["up_axis"]}
    assert not rows["upper"]["turned"] and "robot.yaml" in rows["upper"]["reason"]
    # The global option still forces every file, as before 'auto' existed.
    manifest.write_text(
        manifest.read_text().split("meshes:")[0] + "meshes:\n  collada_up_axis: apply\n"
    )
    result = mjcfbuild.build(manifest, jobs=1, check=False)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert visual_extent(model, "lower") == pytest.approx([0.06, 0.4, 0.1], abs=1e-6)


def test_a_per_file_choice_naming_no_mesh_file_is_refused_at_its_line(robot_folder):
    """A misspelt file would be left to the default without a word (issue 43)."""
    from mjcfbuild.errors import ManifestError

    manifest = simple_manifest(
        robot_folder, extra="meshes:\n  collada_up_axis_files:\n    uper.dae: ignore\n"
    )
    with pytest.raises(ManifestError) as info:
        mjcfbuild.build(manifest, jobs=1)
    line = len(manifest.read_text().splitlines())
    assert info.value.one_line().startswith(
        f"robot.yaml:{line}:5: meshes.collada_up_axis_files[\"uper.dae\"]: 'uper.dae' matches "
        "no mesh file of the robot; did you mean 'upper.dae'? (fix the name, or remove the "
        "entry; the robot's DAE files: lower.dae, upper.dae)"
    ), info.value.one_line()


def test_the_evidence_is_in_the_mesh_frame_and_decides_only_when_clear(robot_folder):
    robot = parse_urdf((robot_folder / "robot.urdf").read_bytes(), "robot.urdf")
    robot.links[1].visuals[0].geometry.mesh_id = "upper"
    (use,) = mesh_uses(robot, "upper")
    assert use.kinds == ["joint", "child joint", "centre of mass"]
    assert use.points[1] == pytest.approx([0, 0, -0.4])
    assert use.boxes[0][0] == pytest.approx(list(LOW)) and use.boxes[0][1] == pytest.approx(
        list(HIGH)
    )
    corners, _ = box_triangles(LOW, HIGH)
    assert decide(as_y_up(corners), "Y_UP", [use]).turned
    assert not decide(corners, "Y_UP", [use]).turned
    assert not decide(corners, "Z_UP", [use]).turned
    # No evidence, or evidence that fits neither reading: kept as written.
    assert not decide(as_y_up(corners), "Y_UP", []).turned
    far = MeshUse("far", [[5.0, 5.0, 5.0]], ["centre of mass"], [])
    assert not decide(as_y_up(corners), "Y_UP", [far]).turned
    assert read_up_axis(robot_folder / "meshes" / "upper.dae") == "Y_UP"
