"""Mesh products: one OBJ per material, a merged file for collision, stable bytes."""

from __future__ import annotations

import mujoco
import pytest

from mjcfbuild.meshes.convert import convert_mesh
from mjcfbuild.meshes.objfile import read_obj_vertices
from tests.conftest import EXAMPLES


def test_single_material_mesh_serves_visual_and_collision(tmp_path):
    summary = convert_mesh(
        EXAMPLES / "arm" / "meshes" / "upper_arm.dae", tmp_path, ["collision", "visual"]
    )
    assert [p.file for p in summary.parts] == ["mesh.obj"]
    assert summary.collision == "mesh.obj"
    assert summary.parts[0].rgba[0] > 0.8


def test_two_materials_give_two_parts_and_a_merged_collision_file(tmp_path):
    summary = convert_mesh(
        EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path, ["collision", "visual"]
    )
    assert [p.file for p in summary.parts] == ["part0.obj", "part1.obj"]
    assert summary.collision == "collision.obj"
    # each OBJ file with its binary copy for the build's compiles (meshes.mshfile)
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "collision.msh",
        "collision.obj",
        "part0.msh",
        "part0.obj",
        "part1.msh",
        "part1.obj",
    ]


def test_visual_only_mesh_has_no_collision_file_and_stale_files_go(tmp_path):
    (tmp_path / "old.obj").write_text("stale")
    summary = convert_mesh(EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path, ["visual"])
    assert summary.collision is None
    assert not (tmp_path / "old.obj").exists()


def test_products_are_reproducible(tmp_path):
    first = convert_mesh(EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path / "a", ["visual"])
    second = convert_mesh(EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path / "b", ["visual"])
    assert first == second
    assert (tmp_path / "a" / "part0.obj").read_bytes() == (
        tmp_path / "b" / "part0.obj"
    ).read_bytes()


def _sphere(path):
    import trimesh

    trimesh.creation.icosphere(subdivisions=3, radius=0.1).export(path)
    return path


def test_visual_and_collision_budgets_are_separate(tmp_path):
    source = _sphere(tmp_path / "ball.stl")  # 1280 faces
    summary = convert_mesh(
        source, tmp_path / "out", ["visual", "collision"], max_faces=1000, collision_max_faces=200
    )
    assert 900 <= summary.parts[0].faces <= 1000
    assert summary.collision == "collision.obj"
    collision = (tmp_path / "out" / "collision.obj").read_text()
    assert 150 <= collision.count("\nf ") <= 200
    assert any("(collision): 1280 faces over the budget of 200" in w for w in summary.warnings)

    # Without a collision budget the visual budget no longer decimates collision geometry.
    summary = convert_mesh(source, tmp_path / "two", ["visual", "collision"], max_faces=1000)
    collision = (tmp_path / "two" / summary.collision).read_text()
    assert collision.count("\nf ") == 1280


def test_the_hull_keeps_at_most_the_vertex_limit_and_stays_inside(tmp_path):
    import numpy as np
    import trimesh

    source = _sphere(tmp_path / "ball.stl")  # its hull has 642 vertices
    summary = convert_mesh(source, tmp_path / "out", ["hull"], max_hull_vertices=32)
    hull = trimesh.load(tmp_path / "out" / summary.hull, process=False)
    assert 16 <= len(hull.vertices) <= 32
    assert np.linalg.norm(hull.vertices, axis=1).max() <= 0.1 + 1e-6  # original (float32) points
    again = convert_mesh(source, tmp_path / "again", ["hull"], max_hull_vertices=32)
    assert again.files == summary.files  # deterministic


TRIANGLE_OBJ = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nf 1 2 3\n"
# urdf-usd-converter's dae_no_normal.dae: one triangle, its normal not indexed
TRIANGLE_DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 0.1 0 0 0 0.1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n">
    <instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"""


@pytest.mark.parametrize("name, text", [("tri.obj", TRIANGLE_OBJ), ("tri.dae", TRIANGLE_DAE)])
def test_a_mesh_of_one_triangle_has_the_four_vertices_mujoco_needs(tmp_path, name, text):
    # MuJoCo refused the product ("invalid sizes in MSH file", naming mjcfbuild's own file);
    # a copy of a corner that no triangle uses makes it a mesh MuJoCo reads, drawn as viewers
    # draw the triangle. Its hull (a policy's) no longer stops qhull, which needs 4 points.
    source = tmp_path / name
    source.write_text(text)
    out = tmp_path / "product"
    summary = convert_mesh(source, out, ["visual", "hull"])
    vertices = read_obj_vertices(out / "mesh.obj")
    assert len(vertices) == 4 and (vertices[3] == vertices[0]).all()
    assert (out / "mesh.obj").read_text().count("\nf ") == 1
    assert summary.hull is not None
    for file in ("mesh.obj", "mesh.msh"):
        model = mujoco.MjModel.from_xml_string(
            f'<mujoco><asset><mesh name="m" file="{out / file}" inertia="shell"/></asset>'
            '<worldbody><body><geom type="mesh" mesh="m" contype="0" conaffinity="0" '
            'density="0"/></body></worldbody></mujoco>'
        )
        assert (model.mesh_vertnum[0], model.mesh_facenum[0]) == (4, 1)
