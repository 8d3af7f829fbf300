"""What a DAE's materials show, checked against pycollada's reading of the same file: the
texture coordinate set a material binds, per-vertex colours and emission."""

from __future__ import annotations

import warnings

import numpy as np

from mjcfbuild.meshes.collada import read_collada
from tests.conftest import write
from tests.meshes.samples import checker_png
from tests.meshes.test_collada import MATERIAL, dae, scene

ST = '<param name="S" type="float"/><param name="T" type="float"/>'
XYZ = '<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>'
TWO_SETS = f"""
<library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="12">0 0 0 1 0 0 1 1 0 0 1 0</float_array>
    <technique_common><accessor source="#pa" count="4" stride="3">{XYZ}</accessor></technique_common></source>
  <source id="t0"><float_array id="t0a" count="8">0 0 1 0 1 1 0 1</float_array>
    <technique_common><accessor source="#t0a" count="4" stride="2">{ST}</accessor></technique_common></source>
  <source id="t1"><float_array id="t1a" count="8">0.5 0.5 0.75 0.5 0.75 0.75 0.5 0.75</float_array>
    <technique_common><accessor source="#t1a" count="4" stride="2">{ST}</accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <polylist material="m" count="1">
    <input semantic="VERTEX" source="#v" offset="0"/>
    <input semantic="TEXCOORD" source="#t0" offset="1" set="0"/>
    <input semantic="TEXCOORD" source="#t1" offset="2" set="1"/>
    <vcount>4</vcount><p>0 0 0 1 1 1 2 2 2 3 3 3</p>
  </polylist>
</mesh></geometry></library_geometries>"""


def bound_instance(input_set: str | None) -> str:
    binding = (
        f'<bind_vertex_input semantic="UVMap" input_semantic="TEXCOORD" input_set="{input_set}"/>'
        if input_set is not None
        else ""
    )
    return (
        '<node><instance_geometry url="#g"><bind_material><technique_common>'
        f'<instance_material symbol="m" target="#mat">{binding}</instance_material>'
        "</technique_common></bind_material></instance_geometry></node>"
    )


def textured(tmp_path, input_set: str | None):
    checker_png(tmp_path / "skin.png")
    body = TWO_SETS + MATERIAL.format(diffuse='<texture texture="samp" texcoord="UVMap"/>')
    return write(tmp_path / "two_sets.dae", dae(body, scene=scene(bound_instance(input_set))))


def corners(positions: np.ndarray, uv: np.ndarray) -> list:
    """Each triangle corner as (x, y, z, u, v), sorted: the same for any triangle order."""
    rows = np.hstack([positions.reshape(-1, 3), uv.reshape(-1, 2)])
    return sorted(map(tuple, np.round(rows, 9).tolist()))


def pycollada_corners(path, material_symbol: str = "m") -> list:
    """The texture coordinates pycollada gives the set the material's binding names."""
    import collada

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpy.matrix inside pycollada
        document = collada.Collada(str(path))
        (bound,) = document.scene.objects("geometry")
        (primitive,) = bound.primitives()
        triangles = primitive.triangleset()
    (binding,) = bound.materialnodebysymbol[material_symbol].inputs
    texcoords = primitive.original.sources["TEXCOORD"]
    index = next(k for k, entry in enumerate(texcoords) if entry[3] == binding[2])
    uv = triangles.texcoordset[index][triangles.texcoord_indexset[index]]
    return corners(triangles.vertex[triangles.vertex_index], uv)


def test_a_texture_reads_the_coordinate_set_its_material_binds(tmp_path):
    path = textured(tmp_path, "1")
    mesh = read_collada(path)
    (part,) = mesh.parts
    assert part.uv is not None
    assert corners(part.vertices[part.faces], part.uv[part.faces]) == pycollada_corners(path)
    assert part.uv.min() == 0.5  # set 1's coordinates, not set 0's
    assert mesh.warnings == []


def test_without_a_binding_the_texture_reads_set_0(tmp_path):
    (part,) = read_collada(textured(tmp_path, None)).parts
    assert part.uv is not None and part.uv.min() == 0.0 and part.uv.max() == 1.0


def test_a_bound_set_the_geometry_lacks_is_said_and_set_0_is_used(tmp_path):
    mesh = read_collada(textured(tmp_path, "7"))
    (part,) = mesh.parts
    assert part.uv is not None and part.uv.max() == 1.0
    (warning,) = mesh.warnings
    assert warning.startswith("two_sets.dae: material 'mat' maps its texture with texture ")
    assert "set 7, which geometry 'g' does not have; the model maps it with set 0" in warning


def test_the_reader_s_warnings_reach_the_mesh_s(tmp_path):
    from mjcfbuild.meshes.load import load_parts

    said: list[str] = []
    load_parts(textured(tmp_path, "7"), warnings=said)
    assert len(said) == 1 and said[0].startswith("two_sets.dae: material 'mat' maps its texture")


RGB = '<param name="R" type="float"/><param name="G" type="float"/><param name="B" type="float"/>'


def coloured(corner_colours: str, colour_index: str, material: str = "") -> str:
    """Two triangles whose corners index the colours ``corner_colours`` (RGB rows)."""
    count = len(corner_colours.split()) // 3
    return f"""
<library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="12">0 0 0 1 0 0 1 1 0 0 1 0</float_array>
    <technique_common><accessor source="#pa" count="4" stride="3">{XYZ}</accessor></technique_common></source>
  <source id="c"><float_array id="ca" count="{count * 3}">{corner_colours}</float_array>
    <technique_common><accessor source="#ca" count="{count}" stride="3">{RGB}</accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles count="2"{material}>
    <input semantic="VERTEX" source="#v" offset="0"/><input semantic="COLOR" source="#c" offset="1"/>
    <p>{colour_index}</p>
  </triangles>
</mesh></geometry></library_geometries>"""


PLAIN = '<node><instance_geometry url="#g"/></node>'


def pycollada_face_colours(path) -> list:
    """Each triangle's corner colours as pycollada reads them, sorted."""
    import collada

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        document = collada.Collada(str(path))
        (bound,) = document.scene.objects("geometry")
        (primitive,) = bound.primitives()
    offset, _, _, _, source = primitive.original.sources["COLOR"][0]
    colours = source.data[primitive.original.index[:, :, offset]]
    return sorted(map(tuple, np.round(colours.mean(axis=1), 6).tolist()))


def test_vertex_colours_colour_the_faces_where_no_material_does(tmp_path):
    # red triangle (0 1 2), blue triangle (0 2 3): each face's corners share a colour
    body = coloured("1 0 0 0 0 1", "0 0 1 0 2 0 0 1 2 1 3 1")
    path = write(tmp_path / "painted.dae", dae(body, scene=scene(PLAIN)))
    mesh = read_collada(path)
    looks = sorted((part.rgba, len(part.faces)) for part in mesh.parts)
    assert looks == [((0.0, 0.0, 1.0, 1.0), 1), ((1.0, 0.0, 0.0, 1.0), 1)]
    ours = sorted(part.rgba[:3] for part in mesh.parts for _ in part.faces)
    assert ours == pycollada_face_colours(path)
    assert mesh.warnings == []


def test_a_face_whose_corners_differ_takes_their_mean_with_a_warning(tmp_path):
    body = coloured("1 0 0 0 0 1", "0 0 1 0 2 1 0 1 2 1 3 1")
    mesh = read_collada(write(tmp_path / "blend.dae", dae(body, scene=scene(PLAIN))))
    assert sorted(part.rgba for part in mesh.parts) == [
        (0.0, 0.0, 1.0, 1.0),
        (0.666667, 0.0, 0.333333, 1.0),
    ]
    (warning,) = mesh.warnings
    assert warning.startswith("blend.dae: its per-vertex colours (COLOR) blend across faces")
    assert "each face with the mean of its corners' colours" in warning


def test_a_material_s_colour_wins_over_vertex_colours_with_a_warning(tmp_path):
    body = coloured("1 0 0 0 0 1", "0 0 1 0 2 0 0 1 2 1 3 1", ' material="m"')
    body += MATERIAL.format(diffuse="<color>0.2 0.6 0.2 1</color>")
    node = (
        '<node><instance_geometry url="#g"><bind_material><technique_common>'
        '<instance_material symbol="m" target="#mat"/></technique_common></bind_material>'
        "</instance_geometry></node>"
    )
    mesh = read_collada(write(tmp_path / "both.dae", dae(body, scene=scene(node))))
    (part,) = mesh.parts
    assert part.rgba == (0.2, 0.6, 0.2, 1.0)
    (warning,) = mesh.warnings
    assert warning.startswith("both.dae: its per-vertex colours (COLOR) are not shown where")


def test_more_vertex_colours_than_parts_are_averaged_with_a_warning(tmp_path):
    shades = " ".join(f"{k / 20:g} 0 0" for k in range(20))
    triangles = " ".join(f"0 {k} 1 {k} 2 {k}" for k in range(20))
    body = coloured(shades, triangles).replace('<triangles count="2"', '<triangles count="20"')
    mesh = read_collada(write(tmp_path / "many.dae", dae(body, scene=scene(PLAIN))))
    (part,) = mesh.parts
    assert part.rgba == (0.475, 0.0, 0.0, 1.0) and len(part.faces) == 20
    (warning,) = mesh.warnings
    assert "(COLOR) hold 20 colours, more than the 16 parts" in warning


def glowing(tmp_path, emission: str):
    body = TWO_SETS + MATERIAL.format(diffuse="<color>0.8 0.4 0 1</color>").replace(
        "<lambert>", f"<lambert><emission><color>{emission} 1</color></emission>"
    )
    node = bound_instance(None)
    return write(tmp_path / "glow.dae", dae(body, scene=scene(node)))


def test_an_emission_in_the_material_s_own_colour_is_its_share(tmp_path):
    mesh = read_collada(glowing(tmp_path, "0.4 0.2 0"))
    (part,) = mesh.parts
    assert part.emission == 0.5
    assert mesh.warnings == []


def test_an_emission_of_another_hue_is_the_closest_share_with_a_warning(tmp_path):
    mesh = read_collada(glowing(tmp_path, "0 0 0.5"))
    (part,) = mesh.parts
    assert part.emission is None  # no share of orange comes closer to blue than none
    (warning,) = mesh.warnings
    assert warning == (
        "glow.dae: material 'mat' glows 0 0 0.5 (<emission>), and a MuJoCo material glows "
        "only in a share of its own colour: the model gives it emission 0"
    )


def test_black_emission_is_no_glow(tmp_path):
    mesh = read_collada(glowing(tmp_path, "0 0 0"))
    assert mesh.parts[0].emission is None and mesh.warnings == []


def coloured_dae(path, rgb: str):
    """A tetrahedron of one material coloured ``rgb``, as CAD exporters write one."""
    body = f"""
<library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="12">0 0 0 0.1 0 0 0 0.1 0 0 0 0.1</float_array>
    <technique_common><accessor source="#pa" count="4" stride="3">{XYZ}</accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles material="m" count="4"><input semantic="VERTEX" source="#v" offset="0"/>
    <p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>
</mesh></geometry></library_geometries>"""
    body += MATERIAL.format(diffuse=f"<color>{rgb} 1</color>")
    return write(path, dae(body, scene=scene(bound_instance(None))))


def test_a_colour_index_beyond_its_source_is_refused_with_its_line(tmp_path):
    import pytest

    from mjcfbuild.errors import InputError

    body = coloured("1 0 0 0 0 1", "0 0 1 0 2 0 0 1 2 1 3 5")
    with pytest.raises(InputError, match=r"uses colour 5, but its source has 2 colours") as error:
        read_collada(write(tmp_path / "bad.dae", dae(body, scene=scene(PLAIN))))
    assert error.value.location is not None and error.value.location.line
