"""The COLLADA reader: units, up axis, polygons, node transforms, materials, textures."""

from __future__ import annotations

import numpy as np
import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.meshes.collada import read_collada
from tests.conftest import write
from tests.meshes.samples import checker_png


def dae(body: str, unit: str = '<unit meter="1"/>', up: str = "Z_UP", scene: str = "") -> str:
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>{unit}<up_axis>{up}</up_axis></asset>
  {body}
  {scene}
</COLLADA>"""


QUAD = """
<library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="12">0 0 0 1 0 0 1 1 0 0 1 0</float_array>
    <technique_common><accessor source="#pa" count="4" stride="3"/></technique_common></source>
  <source id="t"><float_array id="ta" count="8">0 0 1 0 1 1 0 1</float_array>
    <technique_common><accessor source="#ta" count="4" stride="2"/></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <polylist material="m" count="1">
    <input semantic="VERTEX" source="#v" offset="0"/><input semantic="TEXCOORD" source="#t" offset="1"/>
    <vcount>4</vcount><p>0 0 1 1 2 2 3 3</p>
  </polylist>
</mesh></geometry></library_geometries>"""

MATERIAL = """
<library_images><image id="img"><init_from>skin.png</init_from></image></library_images>
<library_effects><effect id="fx"><profile_COMMON>
  <newparam sid="surf"><surface type="2D"><init_from>img</init_from></surface></newparam>
  <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
  <technique sid="c"><lambert><diffuse>{diffuse}</diffuse></lambert></technique>
</profile_COMMON></effect></library_effects>
<library_materials><material id="mat"><instance_effect url="#fx"/></material></library_materials>"""


def scene(node_content: str) -> str:
    return f"""<library_visual_scenes><visual_scene id="s">{node_content}</visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene>"""


INSTANCE = (
    '<instance_geometry url="#g"><bind_material><technique_common>'
    '<instance_material symbol="m" target="#mat"/></technique_common></bind_material></instance_geometry>'
)


def test_polylist_quad_is_fanned_and_colour_comes_from_the_bound_material(tmp_path):
    path = write(
        tmp_path / "q.dae",
        dae(
            QUAD + MATERIAL.format(diffuse="<color>0.1 0.2 0.3 1</color>"),
            scene=scene(f"<node>{INSTANCE}</node>"),
        ),
    )
    (part,) = read_collada(path).parts
    assert part.faces.tolist() == [[0, 1, 2], [0, 2, 3]]
    assert part.rgba == (0.1, 0.2, 0.3, 1.0)
    assert part.texture is None


def test_units_and_node_transforms_are_applied(tmp_path):
    node = f"<node><translate>10 0 0</translate><rotate>0 0 1 90</rotate><scale>2 2 2</scale>{INSTANCE}</node>"
    path = write(
        tmp_path / "q.dae",
        dae(
            QUAD + MATERIAL.format(diffuse="<color>1 1 1 1</color>"),
            unit='<unit meter="0.001"/>',
            scene=scene(node),
        ),
    )
    mesh = read_collada(path)
    assert mesh.unit == 0.001
    # (1, 0, 0) scaled by 2, turned a quarter about z, moved by 10 along x, in millimetres
    assert np.allclose(mesh.parts[0].vertices[1], [0.010, 0.002, 0.0])


def test_instance_node_is_followed(tmp_path):
    library = f'<library_nodes><node id="shared">{INSTANCE}</node></library_nodes>'
    body = QUAD + MATERIAL.format(diffuse="<color>1 0 0 1</color>") + library
    node = '<node><instance_node url="#shared"/></node><node><translate>0 0 1</translate><instance_node url="#shared"/></node>'
    (part,) = read_collada(write(tmp_path / "q.dae", dae(body, scene=scene(node)))).parts
    assert len(part.faces) == 4
    assert part.vertices[:, 2].max() == 1.0


def test_up_axis_is_ignored_unless_asked(tmp_path):
    path = write(
        tmp_path / "q.dae",
        dae(
            QUAD + MATERIAL.format(diffuse="<color>1 1 1 1</color>"),
            up="Y_UP",
            scene=scene(f"<node>{INSTANCE}</node>"),
        ),
    )
    assert np.allclose(read_collada(path).parts[0].vertices[2], [1, 1, 0])
    rotated = read_collada(path, apply_up_axis=True)
    assert rotated.up_axis == "Y_UP"
    assert np.allclose(rotated.parts[0].vertices[2], [1, 0, 1])


def test_texture_is_followed_through_sampler_and_surface(tmp_path):
    checker_png(tmp_path / "skin.png")
    body = QUAD + MATERIAL.format(diffuse='<texture texture="samp" texcoord="UV"/>')
    (part,) = read_collada(
        write(tmp_path / "q.dae", dae(body, scene=scene(f"<node>{INSTANCE}</node>")))
    ).parts
    assert part.texture == tmp_path / "skin.png"
    assert part.uv is not None and part.uv.tolist()[2] == [1.0, 1.0]


def test_broken_files_are_input_errors(tmp_path):
    with pytest.raises(InputError, match="cannot read COLLADA"):
        read_collada(write(tmp_path / "a.dae", "<COLLADA><unclosed"))
    with pytest.raises(InputError, match="not a COLLADA file"):
        read_collada(write(tmp_path / "b.dae", "<model/>"))
    bad_index = QUAD.replace("<p>0 0 1 1 2 2 3 3</p>", "<p>0 0 1 1 2 2 9 3</p>")
    with pytest.raises(InputError, match="out of range"):
        read_collada(
            write(tmp_path / "c.dae", dae(bad_index, scene=scene(f"<node>{INSTANCE}</node>")))
        )


@pytest.mark.parametrize("meter", ["0,001", "abc", "0", "-1", "nan", "1e400"])
def test_a_unit_that_is_no_positive_length_is_an_error_at_its_line(tmp_path, meter):
    """pycollada ignores ``meter="0,001"`` (a decimal comma: millimetres), which would make
    the mesh a thousand times too large; 0 and -1 collapsed or mirrored it."""
    body = QUAD + MATERIAL.format(diffuse="<color>1 1 1 1</color>")
    path = write(
        tmp_path / "u.dae",
        dae(body, unit=f'<unit meter="{meter}"/>', scene=scene(f"<node>{INSTANCE}</node>")),
    )
    with pytest.raises(InputError) as info:
        read_collada(path)
    assert info.value.location.line == 3
    assert f'<unit meter="{meter}">: the length of the file\'s unit in metres' in str(info.value)


@pytest.mark.parametrize(
    ("old", "new", "says"),
    [
        ("<p>0 0 1 1 2 2 3 3</p>", "<p>0 0 1.5 1 2 2 3 3</p>", "<p> holds '1.5' among its whole"),
        ('count="12">0 0 0 1', 'count="12">0 0 0,5 1', "<float_array> holds '0,5' among"),
    ],
    ids=["index-not-whole", "decimal-comma"],
)
def test_numbers_that_do_not_read_are_an_error_at_their_line(tmp_path, old, new, says):
    body = QUAD.replace(old, new) + MATERIAL.format(diffuse="<color>1 1 1 1</color>")
    path = write(tmp_path / "n.dae", dae(body, scene=scene(f"<node>{INSTANCE}</node>")))
    with pytest.raises(InputError) as info:
        read_collada(path)
    assert says in str(info.value) and info.value.location.line is not None


@pytest.mark.parametrize(
    ("transform", "says"),
    [
        ("<lookat>1 0 0 0 0 0 0 0 1</lookat>", "is placed with <lookat>, which mjcfbuild does not"),
        ("<skew>45 0 1 0 1 0 0</skew>", "is placed with <skew>, which mjcfbuild does not apply"),
        ("<translate>1 2</translate>", "a <translate> of node 'n' with 2 numbers (a <translate>"),
    ],
    ids=["lookat", "skew", "short-translate"],
)
def test_a_placement_the_reader_cannot_apply_is_an_error_not_ignored(tmp_path, transform, says):
    body = QUAD + MATERIAL.format(diffuse="<color>1 1 1 1</color>")
    node = f'<node id="n">{transform}{INSTANCE}</node>'
    with pytest.raises(InputError) as info:
        read_collada(write(tmp_path / "t.dae", dae(body, scene=scene(node))))
    assert says in str(info.value)


def _prism_free(body_geometry: str) -> str:
    """A file of one geometry ``g`` (its <mesh> content given) placed once, unbound."""
    return dae(
        f'<library_geometries><geometry id="g"><mesh>{body_geometry}</mesh></geometry>'
        "</library_geometries>",
        scene=scene('<node><instance_geometry url="#g"/></node>'),
    )


# An L-shaped face (2 x 2 with the corner [1, 2] x [1, 2] cut away), written from a corner
# whose fan crosses the notch: area 3, where the fan covers 4.
L_SHAPE = """
  <source id="p"><float_array id="pa" count="18">2 1 0 1 1 0 1 2 0 0 2 0 0 0 0 2 0 0</float_array>
    <technique_common><accessor source="#pa" count="6" stride="3"/></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/>
    <vcount>6</vcount><p>0 1 2 3 4 5</p></polylist>"""


def _area(part) -> float:
    corners = part.vertices[part.faces]
    return float(
        np.linalg.norm(
            np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1
        ).sum()
        / 2
    )


def test_a_concave_polygon_is_ear_clipped_and_keeps_its_winding(tmp_path):
    """A fan from the first corner covered the notch of an L-shaped n-gon (Blender writes
    them as one polygon); rviz's importer clips ears."""
    (part,) = read_collada(write(tmp_path / "l.dae", _prism_free(L_SHAPE))).parts
    assert _area(part) == pytest.approx(3.0)
    corners = part.vertices[part.faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    assert np.all(normals[:, 2] > 0)  # every triangle faces as the polygon does
    # A corner written twice in a row, and polygons of no corners beside it, change nothing.
    doubled = L_SHAPE.replace('count="18">2 1 0 1 1 0', 'count="21">2 1 0 1 1 0 1 1 0')
    doubled = doubled.replace('count="6" stride="3"', 'count="7" stride="3"')
    doubled = doubled.replace(
        "<vcount>6</vcount><p>0 1 2 3 4 5</p>", "<vcount>7 0</vcount><p>0 1 2 3 4 5 6</p>"
    )
    doubled = doubled.replace('<polylist count="1">', '<polylist count="2">')
    (part,) = read_collada(write(tmp_path / "d.dae", _prism_free(doubled))).parts
    assert _area(part) == pytest.approx(3.0)


def test_a_convex_polygon_keeps_its_fan_beside_a_concave_one():
    from mjcfbuild.meshes.collada_polygons import polygon_triangles

    square = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], dtype=float)
    notched = np.array(
        [(2, 1, 0), (1, 1, 0), (1, 2, 0), (0, 2, 0), (0, 0, 0), (2, 0, 0)], dtype=float
    )
    faces = polygon_triangles(np.array([4, 6, 4]), np.vstack([square, notched, square]))
    assert faces[:2].tolist() == [[0, 1, 2], [0, 2, 3]] and faces[-2:].tolist() == [
        [10, 11, 12],
        [10, 12, 13],
    ]
    assert faces[2:6].tolist() != [[4, 5, 6], [4, 6, 7], [4, 7, 8], [4, 8, 9]]  # not the fan


def test_x_up_data_is_turned_as_the_spec_s_axes_say(tmp_path):
    """COLLADA's X_UP: right is -y, up is x, in is z; turned to Z-up, (0, 2, 5) is (-2, -5, 0)
    (it was turned a quarter turn off about the vertical)."""
    point = QUAD.replace("0 0 0 1 0 0 1 1 0 0 1 0", "0 2 5 1 0 0 1 1 0 0 1 0")
    path = write(tmp_path / "x.dae", dae(point, up="X_UP", scene=scene(f"<node>{INSTANCE}</node>")))
    assert np.allclose(read_collada(path, apply_up_axis=True).parts[0].vertices[0], [-2, -5, 0])


def test_an_accessor_s_offset_and_unnamed_params_are_honoured(tmp_path):
    """An accessor starting at value 3, of rows X, (unnamed), Y, Z: the unnamed column is
    skipped, as the spec says (the reader took the first three columns from the start)."""
    body = """
  <source id="p"><float_array id="pa" count="15">9 9 9 0 7 0 0 1 7 0 0 0 7 1 0</float_array>
    <technique_common><accessor source="#pa" count="3" stride="4" offset="3">
      <param name="X" type="float"/><param type="float"/><param name="Y" type="float"/>
      <param name="Z" type="float"/></accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>"""
    (part,) = read_collada(write(tmp_path / "a.dae", _prism_free(body))).parts
    assert part.vertices.tolist() == [[0, 0, 0], [1, 0, 0], [0, 1, 0]]


def test_texture_coordinates_in_the_vertices_are_used(tmp_path):
    checker_png(tmp_path / "skin.png")
    body = QUAD.replace(
        '<input semantic="POSITION" source="#p"/>',
        '<input semantic="POSITION" source="#p"/><input semantic="TEXCOORD" source="#t"/>',
    ).replace('<input semantic="TEXCOORD" source="#t" offset="1"/>', "")
    body = body.replace("<p>0 0 1 1 2 2 3 3</p>", "<p>0 1 2 3</p>")
    body += MATERIAL.format(diffuse='<texture texture="samp" texcoord="UV"/>')
    (part,) = read_collada(
        write(tmp_path / "q.dae", dae(body, scene=scene(f"<node>{INSTANCE}</node>")))
    ).parts
    assert part.texture == tmp_path / "skin.png"
    assert part.uv is not None and part.uv.tolist()[2] == [1.0, 1.0]


def test_the_common_profile_s_colour_wins_over_another_profile_s(tmp_path):
    extra = MATERIAL.format(diffuse="<color>1 0 0 1</color>").replace(
        "</profile_COMMON>",
        '</profile_COMMON><extra><technique profile="X"><phong><diffuse><color>0 1 0 1</color>'
        "</diffuse></phong></technique></extra>",
    )
    path = write(tmp_path / "q.dae", dae(QUAD + extra, scene=scene(f"<node>{INSTANCE}</node>")))
    assert read_collada(path).parts[0].rgba == (1.0, 0.0, 0.0, 1.0)


def test_a_scene_naming_no_visual_scene_and_a_polylist_without_vcount_are_errors(tmp_path):
    missing = dae(QUAD, scene=scene("").replace('url="#s"', 'url="#nope"'))
    with pytest.raises(InputError, match=r"no visual scene of that id") as error:
        read_collada(write(tmp_path / "s.dae", missing))
    assert error.value.location is not None and error.value.location.line
    no_vcount = QUAD.replace("<vcount>4</vcount>", "")
    with pytest.raises(InputError, match=r"has no <vcount>"):
        read_collada(
            write(tmp_path / "v.dae", dae(no_vcount, scene=scene(f"<node>{INSTANCE}</node>")))
        )


@pytest.mark.parametrize(
    ("accessor", "says"),
    [
        ('offset="x"', r'offset="x", which is no index'),
        ("unnamed", r"names none of its <param>s"),
    ],
)
def test_an_accessor_that_gives_no_values_is_an_error_at_its_line(tmp_path, accessor, says):
    body = """
  <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
    <technique_common><accessor source="#pa" count="3" stride="3" OFFSET>PARAMS</accessor>
    </technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>"""
    params = '<param type="float"/>' * 3 if accessor == "unnamed" else XYZ_PARAMS
    body = body.replace("OFFSET", accessor if accessor != "unnamed" else "").replace(
        "PARAMS", params
    )
    with pytest.raises(InputError, match=says) as error:
        read_collada(write(tmp_path / "a.dae", _prism_free(body)))
    assert error.value.location is not None and error.value.location.line


XYZ_PARAMS = (
    '<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>'
)


def test_a_textured_material_keeps_its_texture_where_one_primitive_has_no_coordinates(tmp_path):
    """One primitive with texture coordinates, one without, one textured material: the
    texture was dropped for both (grey); the one without reads it at (0, 0), as rviz does."""
    checker_png(tmp_path / "skin.png")
    plain = (
        '<triangles material="m" count="1"><input semantic="VERTEX" source="#v" offset="0"/>'
        "<p>0 1 2</p></triangles>"
    )
    body = QUAD.replace("</polylist>", "</polylist>" + plain)
    body += MATERIAL.format(diffuse='<texture texture="samp" texcoord="UV"/>')
    (part,) = read_collada(
        write(tmp_path / "q.dae", dae(body, scene=scene(f"<node>{INSTANCE}</node>")))
    ).parts
    assert part.texture == tmp_path / "skin.png"
    assert part.uv is not None and part.uv.tolist()[-1] == [0.0, 0.0]
    assert part.uv.tolist()[2] == [1.0, 1.0]


@pytest.mark.parametrize(
    ("transparent", "transparency", "alpha"),
    [
        # The COLLADA 1.4.1 spec's opacity: A_ONE takes the colour's alpha, RGB_ZERO one
        # minus its luminance, each times <transparency>.
        ('<transparent opaque="A_ONE"><color>1 1 1 0.25</color></transparent>', "1", 0.25),
        ('<transparent opaque="RGB_ZERO"><color>0.3 0.3 0.3 1</color></transparent>', "1", 0.7),
        # Black under RGB_ZERO is opaque whatever the transparency (it was drawn at 0.4).
        ('<transparent opaque="RGB_ZERO"><color>0 0 0 1</color></transparent>', "0.4", 1.0),
        # What exporters write for an opaque part, invisible by the spec: kept opaque.
        ('<transparent opaque="A_ONE"><color>1 1 1 1</color></transparent>', "0", 1.0),
        # No <transparent>: a clear fraction is trusted, 0 and 1 are not.
        ("", "0.5", 0.5),
        ("", "0", 1.0),
    ],
)
def test_transparency_is_the_specs_opacity(tmp_path, transparent, transparency, alpha):
    seen = f"</diffuse>{transparent}<transparency><float>{transparency}</float></transparency>"
    body = QUAD + MATERIAL.format(diffuse="<color>1 0 0 1</color>").replace("</diffuse>", seen)
    path = write(tmp_path / "q.dae", dae(body, scene=scene(f"<node>{INSTANCE}</node>")))
    assert read_collada(path).parts[0].rgba == pytest.approx((1.0, 0.0, 0.0, alpha))


def test_a_file_without_a_scene_shows_nothing_as_rviz_and_pycollada_show_it(tmp_path):
    """Assimp refuses a DAE that names no visual scene ("File came out empty"), so RViz draws
    nothing of it, and pycollada's scene is None: the model has nothing of it either."""
    import collada

    body = QUAD + MATERIAL.format(diffuse="<color>1 0 0 1</color>")
    path = write(tmp_path / "loose.dae", dae(body))
    # (QUAD's accessors name no <param>s, which pycollada needs to read its geometry)
    read = collada.Collada(str(path), ignore=[collada.common.DaeIncompleteError])
    assert read.scene is None
    mesh = read_collada(path)
    assert mesh.parts == [] and not mesh.scene
    assert mesh.warnings == [
        "loose.dae: it has no <scene> (no <instance_visual_scene>), so RViz (whose Assimp "
        "refuses the file) and pycollada draw nothing of it; the model has nothing of it "
        "either, to see or to collide with (put the 1 geometry of its library in a visual "
        "scene that a <scene> names, or re-export the mesh)"
    ]
