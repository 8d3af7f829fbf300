"""Every mesh format real descriptions ship: STL (ASCII, binary), DAE, OBJ, glTF, GLB, PLY."""

from __future__ import annotations

import pytest

from mjcfbuild.meshes.convert import convert_mesh
from mjcfbuild.meshes.load import load_parts
from mjcfbuild.meshes.references import referenced_files
from tests.conftest import EXAMPLES
from tests.meshes import samples


def test_ascii_and_binary_stl(tmp_path):
    (ascii_part,) = load_parts(samples.ascii_stl(tmp_path / "a.stl"))
    assert len(ascii_part.faces) == 20 and ascii_part.rgba is None
    (binary_part,) = load_parts(EXAMPLES / "arm" / "meshes" / "finger.stl")
    assert len(binary_part.faces) == 12


def test_obj_with_its_own_mtl_and_a_texture(tmp_path):
    obj = samples.obj_with_named_mtl_and_texture(tmp_path / "o")
    parts = load_parts(obj)
    textured = [p for p in parts if p.texture is not None]
    plain = [p for p in parts if p.texture is None]
    assert len(textured) == 1 and textured[0].uv is not None
    assert plain[0].rgba == pytest.approx((0.2, 0.8, 0.2, 1.0))
    assert referenced_files(obj) == [tmp_path / "o" / "looks.mtl", tmp_path / "o" / "skin.png"]


@pytest.mark.parametrize("binary", [True, False])
def test_gltf_and_glb_keep_their_texture(tmp_path, binary):
    path = samples.gltf(tmp_path, binary)
    (part,) = load_parts(path)
    assert part.texture is not None and part.uv is not None
    assert part.texture.png.startswith(b"\x89PNG")
    if not binary:
        assert referenced_files(path)  # the .bin buffers are dependencies


def test_ply_face_colours_become_parts(tmp_path):
    parts = load_parts(samples.coloured_ply(tmp_path / "c.ply"))
    assert sorted(p.rgba for p in parts) == [(0.0, 0.0, 1.0, 1.0), (1.0, 0.0, 0.0, 1.0)]


def test_textured_product_has_png_and_uv(tmp_path):
    obj = samples.obj_with_named_mtl_and_texture(tmp_path / "o")
    summary = convert_mesh(obj, tmp_path / "product", ["visual"])
    textured = [p for p in summary.parts if p.texture]
    assert textured[0].texture == "texture0.png"
    assert (tmp_path / "product" / "texture0.png").read_bytes().startswith(b"\x89PNG")
    assert b"\nvt " in (tmp_path / "product" / textured[0].file).read_bytes()


def test_faces_over_the_budget_are_simplified_with_a_warning(tmp_path):
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=5)
    path = tmp_path / "dense.stl"
    sphere.export(path)
    summary = convert_mesh(path, tmp_path / "product", ["visual"], max_faces=1000)
    assert summary.faces <= 1000
    assert "simplified" in summary.warnings[0]


def test_hull_file_when_asked(tmp_path):
    summary = convert_mesh(
        EXAMPLES / "arm" / "meshes" / "forearm.obj", tmp_path, ["hull", "visual"]
    )
    assert summary.hull == "hull.obj" and summary.collision is None
