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
from tests.meshes.pycollada_reference import (
    mjcfbuild_triangles,
    pycollada_triangles,
    triangle_mismatch,
)
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


SKIN = """<library_controllers><controller id="skin"><skin source="#g">
  <bind_shape_matrix>{bind_shape}</bind_shape_matrix>
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


def skinned(tmp_path, bind_shape: str):
    body = geometry(f'<triangles count="1">{VERTEX}<p>0 1 2</p></triangles>')
    body += SKIN.format(bind_shape=bind_shape)
    node = '<node><translate>0 0 1</translate><instance_controller url="#skin"/></node>'
    return write(tmp_path / "skin.dae", dae(body, scene=scene(node)))


def test_skinned_geometry_is_read_in_its_bind_pose(tmp_path):
    path = skinned(tmp_path, "1 0 0 0  0 1 0 0  0 0 1 2  0 0 0 1")
    mesh = read_collada(path)
    assert sum(len(part.faces) for part in mesh.parts) == 1
    assert np.allclose(mesh.parts[0].vertices[:, 2], 3.0)  # node 1 m + bind shape 2 m
    reference = pycollada_triangles(path)
    assert triangle_mismatch(mjcfbuild_triangles(path), reference.triangles) is None
    assert mesh.warnings == [
        "skin.dae: controller 'skin' skins geometry 'g': the model draws it in its bind pose, "
        "placed by its <bind_shape_matrix> as pycollada places it (RViz draws it without that "
        "matrix), not posed by its joints"
    ]


def test_a_skin_at_the_identity_says_only_that_its_joints_do_not_pose_it(tmp_path):
    mesh = read_collada(skinned(tmp_path, "1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1"))
    (warning,) = mesh.warnings
    assert "RViz" not in warning and warning.endswith("not posed by its joints")


def test_a_bind_shape_matrix_that_is_no_matrix_is_refused_as_pycollada_refuses_it(tmp_path):
    import collada

    path = skinned(tmp_path, "1 0 0 0  0 1 0 0  0 0 1 2")
    with pytest.raises(collada.common.DaeMalformedError):
        collada.Collada(str(path))
    with pytest.raises(
        InputError, match=r"<bind_shape_matrix> of controller 'skin' has 12 numbers"
    ):
        read_collada(path)


def test_a_morph_draws_its_base_mesh_and_says_its_targets_are_left_out(tmp_path):
    morph = """<library_controllers><controller id="morph"><morph source="#g" method="NORMALIZED">
      <source id="t"><IDREF_array id="ta" count="1">g</IDREF_array>
        <technique_common><accessor source="#ta" count="1" stride="1"><param name="IDREF" type="IDREF"/></accessor></technique_common></source>
      <source id="w"><float_array id="wa" count="1">0.5</float_array>
        <technique_common><accessor source="#wa" count="1" stride="1"><param name="MORPH_WEIGHT" type="float"/></accessor></technique_common></source>
      <targets><input semantic="MORPH_TARGET" source="#t"/><input semantic="MORPH_WEIGHT" source="#w"/></targets>
    </morph></controller></library_controllers>"""
    body = geometry(f'<triangles count="1">{VERTEX}<p>0 1 2</p></triangles>') + morph
    node = '<node><instance_controller url="#morph"/></node>'
    mesh = read_collada(write(tmp_path / "morph.dae", dae(body, scene=scene(node))))
    assert sum(len(part.faces) for part in mesh.parts) == 1
    assert mesh.warnings == [
        "morph.dae: controller 'morph' morphs geometry 'g': the model draws its base mesh, as "
        "RViz does, without its morph targets"
    ]


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
