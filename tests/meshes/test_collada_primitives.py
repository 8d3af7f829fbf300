"""Every surface primitive of a DAE is read, checked against independent readers (trimesh,
which reads DAE through pycollada): strips, fans, skinned geometry. What cannot be read is an
error naming it, never a silent gap. Every DAE file of the description wheels is compared with
pycollada in test_collada_parity.py."""

from __future__ import annotations

import numpy as np
import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.meshes.collada import read_collada
from tests.conftest import write
from tests.meshes.test_collada import dae, scene

POINTS = """
<source id="p"><float_array id="pa" count="18">0 0 0 1 0 0 0 1 0 1 1 0 2 0 0 2 1 0</float_array>
  <technique_common><accessor source="#pa" count="6" stride="3"><param name="X" type="float"/>
  <param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>"""
VERTEX = '<input semantic="VERTEX" source="#v" offset="0"/>'


def geometry(primitives: str) -> str:
    return f'<library_geometries><geometry id="g"><mesh>{POINTS}{primitives}</mesh></geometry></library_geometries>'


def area_vector(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """The sum of the faces' area vectors: the area, and which way the faces wind."""
    corners = vertices[faces]
    return 0.5 * np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]).sum(axis=0)


def ours(path):
    mesh = read_collada(path)
    faces = sum(len(part.faces) for part in mesh.parts)
    vector = sum(area_vector(part.vertices, part.faces) for part in mesh.parts)
    return faces, vector


def trimesh_reading(path):
    import trimesh

    mesh = trimesh.load(str(path), force="mesh", process=False)
    return len(mesh.faces), area_vector(np.asarray(mesh.vertices), np.asarray(mesh.faces))


def test_strips_and_fans_are_read_like_trimesh_reads_them(tmp_path):
    body = geometry(
        f'<triangles count="1">{VERTEX}<p>0 1 2</p></triangles>'
        f'<tristrips count="1">{VERTEX}<p>1 3 4 5</p></tristrips>'
        f'<trifans count="1">{VERTEX}<p>0 1 3 2</p></trifans>'
    )
    path = write(
        tmp_path / "strips.dae",
        dae(body, scene=scene('<node><instance_geometry url="#g"/></node>')),
    )
    faces, vector = ours(path)
    assert faces == 5
    reference_faces, reference_vector = trimesh_reading(path)
    assert faces == reference_faces
    np.testing.assert_allclose(vector, reference_vector, atol=1e-12)


def test_skinned_geometry_is_read_in_its_bind_pose(tmp_path):
    controller = """<library_controllers><controller id="skin"><skin source="#g">
      <bind_shape_matrix>1 0 0 0  0 1 0 0  0 0 1 2  0 0 0 1</bind_shape_matrix>
      <source id="jn"><Name_array id="jna" count="1">bone</Name_array>
        <technique_common><accessor source="#jna" count="1" stride="1"><param name="JOINT" type="name"/></accessor></technique_common></source>
      <source id="ib"><float_array id="iba" count="16">1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</float_array>
        <technique_common><accessor source="#iba" count="1" stride="16"><param name="TRANSFORM" type="float4x4"/></accessor></technique_common></source>
      <source id="w"><float_array id="wa" count="1">1</float_array>
        <technique_common><accessor source="#wa" count="1" stride="1"><param name="WEIGHT" type="float"/></accessor></technique_common></source>
      <joints><input semantic="JOINT" source="#jn"/><input semantic="INV_BIND_MATRIX" source="#ib"/></joints>
      <vertex_weights count="6"><input semantic="JOINT" source="#jn" offset="0"/><input semantic="WEIGHT" source="#w" offset="1"/>
        <vcount>1 1 1 1 1 1</vcount><v>0 0 0 0 0 0 0 0 0 0 0 0</v></vertex_weights>
    </skin></controller></library_controllers>"""
    body = geometry(f'<triangles count="1">{VERTEX}<p>0 1 2</p></triangles>') + controller
    node = '<node><translate>0 0 1</translate><instance_controller url="#skin"/></node>'
    path = write(tmp_path / "skin.dae", dae(body, scene=scene(node)))
    mesh = read_collada(path)
    assert sum(len(part.faces) for part in mesh.parts) == 1
    assert np.allclose(mesh.parts[0].vertices[:, 2], 3.0)  # node 1 m + bind shape 2 m
    import collada

    document = collada.Collada(str(path))
    (bound,) = document.scene.objects("controller")
    assert sum(len(primitive) for primitive in bound.primitives()) == 1


def test_an_unreadable_primitive_is_named(tmp_path):
    body = geometry(
        f'<triangles count="1">{VERTEX}<p>0 1 2</p></triangles>'
        f'<polygons count="1">{VERTEX}<ph><p>0 1 3 2</p><h>0 1 2</h></ph></polygons>'
    )
    path = write(
        tmp_path / "holes.dae", dae(body, scene=scene('<node><instance_geometry url="#g"/></node>'))
    )
    with pytest.raises(InputError, match=r"polygons with holes \(<ph>\)"):
        read_collada(path)
    body = geometry(f'<splines count="1">{VERTEX}<p>0 1 2</p></splines>')
    path = write(
        tmp_path / "spline.dae",
        dae(body, scene=scene('<node><instance_geometry url="#g"/></node>')),
    )
    with pytest.raises(InputError, match="<splines>"):
        read_collada(path)
