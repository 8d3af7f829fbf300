"""Mesh products: one OBJ per material, a merged file for collision, stable bytes."""

from __future__ import annotations

from mjcfbuild.meshes.convert import convert_mesh
from tests.conftest import EXAMPLES


def test_single_material_mesh_serves_visual_and_collision(tmp_path):
    summary = convert_mesh(
        EXAMPLES / "arm" / "meshes" / "upper_arm.dae", tmp_path, ["collision", "visual"]
    )
    assert [p["file"] for p in summary["parts"]] == ["mesh.obj"]
    assert summary["collision"] == "mesh.obj"
    assert summary["parts"][0]["rgba"][0] > 0.8


def test_two_materials_give_two_parts_and_a_merged_collision_file(tmp_path):
    summary = convert_mesh(
        EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path, ["collision", "visual"]
    )
    assert [p["file"] for p in summary["parts"]] == ["part0.obj", "part1.obj"]
    assert summary["collision"] == "collision.obj"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["collision.obj", "part0.obj", "part1.obj"]


def test_visual_only_mesh_has_no_collision_file_and_stale_files_go(tmp_path):
    (tmp_path / "old.obj").write_text("stale")
    summary = convert_mesh(EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path, ["visual"])
    assert summary["collision"] is None
    assert not (tmp_path / "old.obj").exists()


def test_products_are_reproducible(tmp_path):
    first = convert_mesh(EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path / "a", ["visual"])
    second = convert_mesh(EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path / "b", ["visual"])
    assert first == second
    assert (tmp_path / "a" / "part0.obj").read_bytes() == (
        tmp_path / "b" / "part0.obj"
    ).read_bytes()
