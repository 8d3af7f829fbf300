"""Convex decomposition: the hull where it is close enough, CoACD elsewhere; reproducible."""

from __future__ import annotations

import numpy as np
import trimesh

from mjcfbuild.collision.decompose import coacd_arguments, decompose
from mjcfbuild.manifest.models import CoacdParams
from mjcfbuild.meshes.objfile import obj_bytes
from tests.collision.test_concavity import u_shape


def write_mesh(path, mesh):
    path.write_bytes(obj_bytes(mesh.vertices, mesh.faces))
    return path


def params(**overrides) -> dict:
    """The manifest's default decompose parameters, as a build step gets them."""
    return CoacdParams(**overrides).model_dump()


def test_a_box_keeps_its_hull_without_coacd(tmp_path):
    box = write_mesh(tmp_path / "box.obj", trimesh.creation.box([0.3, 0.2, 0.1]))
    summary = decompose(box, params(), tmp_path / "out")
    assert summary["method"] == "hull"
    assert summary["parts"] == ["part000.obj"]
    assert summary["coacd"] is None
    assert summary["hull_concavity"] < 1e-9 and summary["concavity"] < 1e-9
    part = trimesh.load(tmp_path / "out" / "part000.obj", process=False)
    assert np.isclose(part.volume, 0.3 * 0.2 * 0.1)


def test_a_u_is_decomposed_closer_than_its_hull(tmp_path):
    # (Same bytes from run to run, folder to folder, -j 1 and 2: tests/engine.)
    source = write_mesh(tmp_path / "u.obj", u_shape())
    first = decompose(source, params(), tmp_path / "one")
    assert first["method"] == "coacd"
    assert len(first["parts"]) >= 2
    assert first["hull_concavity"] > 0.3  # 0.4 by hand, see test_concavity
    assert first["concavity"] < first["hull_concavity"] / 2
    assert first["seconds"] > 0
    for name in first["parts"]:
        part = trimesh.load(tmp_path / "one" / name, process=False)
        assert np.isclose(part.volume, part.convex_hull.volume, rtol=1e-6)


def test_the_tolerance_decides_between_hull_and_coacd(tmp_path):
    u = write_mesh(tmp_path / "u.obj", u_shape())
    box = write_mesh(tmp_path / "box.obj", trimesh.creation.box([0.3, 0.2, 0.1]))
    # A tolerance above the U's hull error keeps its hull.
    assert decompose(u, params(hull_tolerance=0.5), tmp_path / "a")["method"] == "hull"
    # 0 turns the shortcut off: CoACD runs even on a box, and finds one part.
    boxed = decompose(box, params(hull_tolerance=0), tmp_path / "b")
    assert boxed["method"] == "coacd" and len(boxed["parts"]) == 1


def test_coacd_parameters_are_scaled_to_the_threshold_and_bounded_by_the_manifest():
    box = trimesh.creation.box([1, 1, 1])
    scaled = coacd_arguments(params(), box.vertices, box.faces)
    assert scaled["preprocess_resolution"] == 20  # 1 / 0.05, CoACD's default is 50
    assert scaled["mcts_iterations"] == 20 and scaled["mcts_max_depth"] == 2
    assert scaled["resolution"] == 1000
    assert "hull_tolerance" not in scaled and "scale_to_mesh" not in scaled
    assert scaled["apx_mode"] == "ch"
    finer = coacd_arguments(params(threshold=0.02), box.vertices, box.faces)
    assert finer["preprocess_resolution"] == 50  # 1 / 0.02, within the manifest's 50
    # A mesh with more triangles than the remesh would have is remeshed even if closed.
    sphere = trimesh.creation.icosphere(subdivisions=5)  # 20480 triangles > 16 * 20^2
    assert coacd_arguments(params(), sphere.vertices, sphere.faces)["preprocess_mode"] == "on"
    assert coacd_arguments(params(), box.vertices, box.faces)["preprocess_mode"] == "auto"
    # Off: the manifest's parameters as they are.
    plain = coacd_arguments(params(scale_to_mesh=False), box.vertices, box.faces)
    assert plain["preprocess_resolution"] == 50 and plain["mcts_iterations"] == 150


def test_a_triangle_is_its_own_flat_hull_not_an_error_naming_the_product(tmp_path):
    # CoACD made no part of one triangle, and the error named mjcfbuild's product file; the
    # triangle as its own part lets the assembly say in one line that the mesh is flat.
    triangle = tmp_path / "tri.obj"
    triangle.write_text("v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0\nf 1 2 3\n")  # as a product
    summary = decompose(triangle, params(), tmp_path / "out")
    assert summary["method"] == "hull" and summary["parts"] == ["part000.obj"]
    part = trimesh.load(tmp_path / "out" / "part000.obj", process=False)
    assert sorted(map(tuple, np.round(part.vertices, 9))) == [(0, 0, 0), (0, 0.1, 0), (0.1, 0, 0)]
