"""OBJ output: exact, reproducible, readable by trimesh and MuJoCo."""

from __future__ import annotations

import mujoco
import numpy as np
import trimesh

from mjcfbuild.meshes.objfile import obj_bytes


def cube():
    return trimesh.creation.box(extents=[1, 2, 3])


def test_bytes_are_reproducible_and_negative_zero_free():
    mesh = cube()
    vertices = mesh.vertices * np.array([1, -1, 1])  # mirroring creates -0.0
    first = obj_bytes(vertices, mesh.faces)
    assert first == obj_bytes(vertices.copy(), mesh.faces.copy())
    assert b"-0 " not in first and b"-0\n" not in first


def test_round_trip_through_trimesh(tmp_path):
    mesh = cube()
    path = tmp_path / "c.obj"
    path.write_bytes(obj_bytes(mesh.vertices, mesh.faces))
    loaded = trimesh.load(path, process=False)
    assert np.allclose(loaded.vertices, mesh.vertices)
    assert np.array_equal(loaded.faces, mesh.faces)


def test_mujoco_loads_it_with_texture_coordinates(tmp_path):
    mesh = cube()
    uv = np.random.default_rng(0).random((len(mesh.vertices), 2))
    (tmp_path / "c.obj").write_bytes(obj_bytes(mesh.vertices, mesh.faces, uv))
    model = mujoco.MjModel.from_xml_string(
        f'<mujoco><asset><mesh file="{tmp_path / "c.obj"}"/></asset>'
        '<worldbody><geom type="mesh" mesh="c"/></worldbody></mujoco>'
    )
    assert model.nmeshface == 12
    assert model.nmeshtexcoord > 0
