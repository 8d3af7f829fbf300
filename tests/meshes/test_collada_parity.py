"""mjcfbuild's COLLADA reader gives pycollada's triangles (1e-9 m, after node transforms and
<unit>): on generated files that reuse ids in every geometry as exporters do, and on every DAE
file of the description wheels the robot suite downloads. Where the readings could disagree
(an id that names two different elements) or a reading would be partial or collapsed, the
reader refuses the file in one line naming it."""

from __future__ import annotations

import hashlib
import zipfile
from pathlib import Path

import numpy as np
import pytest

from mjcfbuild.errors import EXIT_INPUT, InputError
from mjcfbuild.meshes.collada import read_collada
from tests.conftest import write
from tests.meshes.pycollada_reference import (
    mjcfbuild_triangles,
    pycollada_triangles,
    triangle_mismatch,
)

# Three solids of different sizes: a reader that resolves "verts" to the wrong geometry's
# source reads too few vertices (an index out of range) or someone else's (silently wrong).
TETRAHEDRON = ([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3])
BOX_FACES = "0 2 1 0 3 2 4 5 6 4 6 7 0 1 5 0 5 4 1 2 6 1 6 5 2 3 7 2 7 6 3 0 4 3 4 7"
BOX = (
    [0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0, 0, 0, 3, 2, 0, 3, 2, 1, 3, 0, 1, 3],
    [int(i) for i in BOX_FACES.split()],
)
OCTAHEDRON = (
    [1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1],
    [0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5],
)


XYZ = '<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>'


def _numbers(values) -> str:
    return " ".join(str(v) for v in values)


def geometry(geometry_id: str, solid, source_id: str = "verts", vertex_url: str = "") -> str:
    """A <geometry> whose source, array and vertices ids are the same in every geometry."""
    points, triangles = solid
    normals = [0, 0, 1] * (len(points) // 3)
    vertex_url = vertex_url or f"#{source_id}-vertices"
    return f"""
<geometry id="{geometry_id}"><mesh>
  <source id="{source_id}"><float_array id="{source_id}-array" count="{len(points)}">{_numbers(points)}</float_array>
    <technique_common><accessor source="#{source_id}-array" count="{len(points) // 3}" stride="3">{XYZ}</accessor></technique_common></source>
  <source id="norms"><float_array id="norms-array" count="{len(normals)}">{_numbers(normals)}</float_array>
    <technique_common><accessor source="#norms-array" count="{len(normals) // 3}" stride="3">{XYZ}</accessor></technique_common></source>
  <vertices id="{source_id}-vertices"><input semantic="POSITION" source="#{source_id}"/></vertices>
  <triangles material="mat" count="{len(triangles) // 3}">
    <input semantic="VERTEX" source="{vertex_url}" offset="0"/>
    <input semantic="NORMAL" source="#norms" offset="0"/>
    <p>{_numbers(triangles)}</p>
  </triangles>
</mesh></geometry>"""


def material(material_id: str, rgba: str, effect_id: str) -> tuple[str, str]:
    """(<material>, <effect>) giving a Lambert colour."""
    return (
        f'<material id="{material_id}"><instance_effect url="#{effect_id}"/></material>',
        f'<effect id="{effect_id}"><profile_COMMON><technique sid="c"><lambert><diffuse>'
        f"<color>{rgba}</color></diffuse></lambert></technique></profile_COMMON></effect>",
    )


def instance(geometry_id: str, target: str = "red") -> str:
    return (
        f'<instance_geometry url="#{geometry_id}"><bind_material><technique_common>'
        f'<instance_material symbol="mat" target="#{target}"/></technique_common></bind_material>'
        "</instance_geometry>"
    )


def document(
    geometries: str,
    nodes: str,
    library_nodes: str = "",
    unit: str = "0.001",
    materials: tuple[tuple[str, str], ...] = (),
) -> str:
    materials = materials or (
        material("red", "1 0 0 1", "red-fx"),
        material("blue", "0 0 1 1", "blue-fx"),
    )
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="millimeter" meter="{unit}"/><up_axis>Z_UP</up_axis></asset>
  <library_effects>{"".join(effect for _, effect in materials)}</library_effects>
  <library_materials>{"".join(m for m, _ in materials)}</library_materials>
  <library_geometries>{geometries}</library_geometries>
  <library_nodes>{library_nodes}</library_nodes>
  <library_visual_scenes><visual_scene id="scene">{nodes}</visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>"""


SOLIDS = (
    geometry("tetrahedron", TETRAHEDRON) + geometry("box", BOX) + geometry("octahedron", OCTAHEDRON)
)
# Nested transforms of every kind, a mirroring node, and one library node instanced twice.
NODES = (
    '<node id="hip"><matrix>0 -1 0 100  1 0 0 20  0 0 1 -30  0 0 0 1</matrix>'
    '<node id="thigh"><translate>5 6 7</translate><rotate>0.6 0 0.8 33</rotate><scale>2 2 0.5</scale>'
    f"{instance('tetrahedron')}</node></node>"
    f'<node id="mirror"><scale>-1 1 1</scale><translate>0 40 0</translate>{instance("box", "blue")}</node>'
    '<node id="left"><translate>0 0 50</translate><instance_node url="#foot"/></node>'
    '<node id="right"><rotate>0 0 1 180</rotate><instance_node url="#foot"/></node>'
)
FOOT = f'<node id="foot"><rotate>0 1 0 -90</rotate><translate>3 0 0</translate>{instance("octahedron")}</node>'


def test_ids_reused_in_every_geometry_read_as_pycollada_reads_them(tmp_path):
    path = write(tmp_path / "leg.dae", document(SOLIDS, NODES, FOOT))
    ours = mjcfbuild_triangles(path)
    assert len(ours) == 4 + 12 + 2 * 8
    reference = pycollada_triangles(path)
    assert reference.skipped == []
    assert triangle_mismatch(ours, reference.triangles) is None
    # in millimetres: the box is 2 x 1 x 3 mm wherever it was mirrored to
    mesh = read_collada(path)
    colours = {part.material: part.rgba for part in mesh.parts}
    assert colours == {"red": (1.0, 0.0, 0.0, 1.0), "blue": (0.0, 0.0, 1.0, 1.0)}
    (box,) = [part for part in mesh.parts if part.material == "blue"]
    np.testing.assert_allclose(np.ptp(box.vertices, axis=0), [0.002, 0.001, 0.003], atol=1e-12)


def test_a_comment_among_a_nodes_transforms_is_skipped_as_pycollada_skips_it(tmp_path):
    # roboschool's multisense head_camera.dae comments out a <matrix> inside a <node>: the
    # comment was taken for an element and the conversion stopped with a ValueError.
    nodes = (
        '<node id="cam"><!--matrix sid="matrix">1 0 0 9 0 1 0 9 0 0 1 9 0 0 0 1</matrix-->'
        f"<translate>0 0 5</translate><?pi ignored?>{instance('box')}</node>"
    )
    path = write(tmp_path / "camera.dae", document(SOLIDS, nodes))
    ours = mjcfbuild_triangles(path)
    assert len(ours) == 12
    assert triangle_mismatch(ours, pycollada_triangles(path).triangles) is None
    (box,) = read_collada(path).parts
    np.testing.assert_allclose(box.vertices[:, 2].min(), 0.005)  # the translate, in mm


def test_the_comparison_sees_a_wrong_reading(tmp_path):
    """The differential check can fail: another geometry's vertices are a mismatch."""
    path = write(tmp_path / "leg.dae", document(SOLIDS, NODES, FOOT))
    ours = mjcfbuild_triangles(path)
    shifted = ours.copy()
    shifted[0, 0, 0] += 1e-8
    assert triangle_mismatch(shifted, ours) is not None
    assert triangle_mismatch(ours[::-1, ::-1], ours) is not None  # winding reversed
    assert triangle_mismatch(ours[::-1], ours) is None  # order does not matter
    # Corners equal but for rounding may start a triangle at another corner: the same triangle.
    tied = np.array([[[0.0, 0.0, 0.2], [0.1, 0.0, 0.3], [0.0, 0.0, 0.1]]])
    rounded = np.roll(tied, 1, axis=1)
    rounded[0, 1, 0] -= 1e-17  # this reading's lowest corner is another one
    assert triangle_mismatch(np.concatenate([ours, tied]), np.concatenate([ours, rounded])) is None


def test_units_scale_the_document(tmp_path):
    metres = mjcfbuild_triangles(write(tmp_path / "m.dae", document(SOLIDS, NODES, FOOT, "1")))
    inches = write(tmp_path / "in.dae", document(SOLIDS, NODES, FOOT, "0.0254"))
    np.testing.assert_allclose(mjcfbuild_triangles(inches), metres * 0.0254, atol=1e-12)
    assert (
        triangle_mismatch(mjcfbuild_triangles(inches), pycollada_triangles(inches).triangles)
        is None
    )


def test_a_rotation_axis_is_normalised_where_pycollada_shears(tmp_path):
    """COLLADA's <rotate> names an axis; pycollada uses it unnormalised (a shear for any other
    length), mjcfbuild turns about it. The parity test above uses unit axes."""
    nodes = f"<node><rotate>0 0 2 90</rotate>{instance('box')}</node>"
    path = write(tmp_path / "axis.dae", document(SOLIDS, nodes, unit="1"))
    ours = mjcfbuild_triangles(path)
    np.testing.assert_allclose(np.ptp(ours.reshape(-1, 3), axis=0), [1, 2, 3], atol=1e-12)
    assert triangle_mismatch(ours, pycollada_triangles(path).triangles) is not None


def test_a_unique_id_in_another_geometry_is_followed(tmp_path):
    """COLLADA ids are document-wide: an input may name another geometry's source when the id
    names one element only."""
    geometries = geometry("tetrahedron", TETRAHEDRON, "tv") + geometry(
        "again", TETRAHEDRON, "other", vertex_url="#tv-vertices"
    )
    nodes = f"<node>{instance('again')}</node>"
    path = write(tmp_path / "shared.dae", document(geometries, nodes))
    np.testing.assert_allclose(
        mjcfbuild_triangles(path),
        np.reshape(TETRAHEDRON[0], (-1, 3))[TETRAHEDRON[1]].reshape(-1, 3, 3) * 1e-3,
    )


def test_an_id_that_names_two_different_sources_is_refused_with_both_lines(tmp_path):
    geometries = (
        geometry("tetrahedron", TETRAHEDRON, "a")
        + geometry("box", BOX, "a")
        + geometry("lost", TETRAHEDRON, "b", vertex_url="#a-vertices")
    )
    text = document(geometries, f"<node>{instance('lost')}</node>")
    path = write(tmp_path / "ambiguous.dae", text)
    with pytest.raises(InputError) as raised:
        read_collada(path)
    lines = text.splitlines()
    vertices_lines = [i + 1 for i, line in enumerate(lines) if '<vertices id="a-vertices"' in line]
    input_line = [i + 1 for i, line in enumerate(lines) if 'source="#a-vertices"' in line][-1]
    error = raised.value
    assert f"lines {vertices_lines[0]} and {vertices_lines[1]}" in error.message
    assert "id 'a-vertices' names 2 different <vertices>" in error.message
    assert error.exit_code == EXIT_INPUT
    assert error.one_line().startswith(f"{path}:{input_line}: ")
    assert "\n" not in error.one_line()


def test_identical_copies_under_one_id_are_not_ambiguous(tmp_path):
    red = material("red", "1 0 0 1", "red-fx")
    path = write(
        tmp_path / "copies.dae",
        document(SOLIDS, NODES, FOOT, materials=(red, red, material("blue", "0 0 1 1", "b"))),
    )
    assert {p.material: p.rgba for p in read_collada(path).parts}["red"] == (1.0, 0.0, 0.0, 1.0)


def test_two_different_materials_under_one_id_are_refused(tmp_path):
    materials = (
        material("red", "1 0 0 1", "red-fx"),
        material("red", "0 1 0 1", "green-fx"),
        material("blue", "0 0 1 1", "blue-fx"),
    )
    path = write(tmp_path / "colours.dae", document(SOLIDS, NODES, FOOT, materials=materials))
    with pytest.raises(InputError, match=r"id 'red' names 2 different <material> elements"):
        read_collada(path)


def test_a_collapsed_primitive_is_refused(tmp_path):
    one_point = ([0.5, 0.5, 0.5] * 8, BOX[1])
    path = write(
        tmp_path / "point.dae",
        document(geometry("box", one_point), f"<node>{instance('box')}</node>"),
    )
    with pytest.raises(
        InputError, match=r"all 12 faces of a <triangles> of geometry 'box' collapse"
    ):
        read_collada(path)


@pytest.mark.parametrize(
    ("nodes", "message"),
    [
        (f"<node>{instance('missing')}</node>", "<instance_geometry> refers to '#missing'"),
        ('<node><instance_node url="#nowhere"/></node>', "<instance_node> refers to '#nowhere'"),
    ],
)
def test_a_dangling_instance_is_refused_not_left_out(tmp_path, nodes, message):
    path = write(tmp_path / "partial.dae", document(SOLIDS, nodes))
    with pytest.raises(InputError, match=message):
        read_collada(path)


def test_an_index_beyond_its_own_source_is_refused_with_its_line(tmp_path):
    """Scoped lookups no longer borrow a larger geometry's source: the index is out of range."""
    too_far = (TETRAHEDRON[0], [*TETRAHEDRON[1][:-1], 7])
    text = document(
        geometry("tetrahedron", too_far) + geometry("box", BOX),
        f"<node>{instance('tetrahedron')}</node>",
    )
    path = write(tmp_path / "far.dae", text)
    with pytest.raises(InputError, match="uses vertex 7, but its source has 4 vertices") as raised:
        read_collada(path)
    assert raised.value.location is not None and raised.value.location.line == next(
        i + 1 for i, line in enumerate(text.splitlines()) if "<triangles" in line
    )


def test_a_truncated_index_list_is_refused(tmp_path):
    """count says 12 triangles, the list holds 11: a file cut short is not read in part."""
    text = document(geometry("box", BOX), f"<node>{instance('box')}</node>")
    cut = text.replace(" 3 4 7</p>", "</p>")
    path = write(tmp_path / "cut.dae", cut)
    with pytest.raises(InputError, match=r'says count="12" but its index list holds 11'):
        read_collada(path)


def test_a_second_index_list_is_refused_not_dropped(tmp_path):
    text = document(geometry("box", BOX), f"<node>{instance('box')}</node>")
    twice = text.replace("</p>", "</p><p>0 1 2</p>")
    path = write(tmp_path / "twice.dae", twice)
    with pytest.raises(InputError, match=r"has 2 <p> index lists \(COLLADA allows one\)"):
        read_collada(path)


# --- every DAE file of the description wheels the robot suite downloads ---------------------

# pycollada skips these files' geometry after ignoring an error of its own (and so reads no
# triangles): a texture surface the effect refers to is missing.
PYCOLLADA_CANNOT_READ = {"anymal_b_simple_description/meshes/foot/anymal_foot.dae"}
# Not XML: the tail of an older version follows </COLLADA> (no URDF names the file); both
# readers refuse it, mjcfbuild with its name and line.
NOT_XML = {"lbr_iiwa_14_r820/visual/base_link2.dae"}


def _wheel_dae_files(tmp_path: Path) -> list[Path]:
    from bench import other_wheels, robot_data

    with zipfile.ZipFile(robot_data.wheel()) as archive:
        names = [n for n in archive.namelist() if n.lower().endswith(".dae")]
        for name in names:
            archive.extract(name, tmp_path)
    files = [tmp_path / name for name in names]
    first_robot_of = {robot.wheel: robot for robot in reversed(list(other_wheels.ROBOTS.values()))}
    for robot in first_robot_of.values():
        other_wheels.unpack(robot)
        root = other_wheels.wheel_root(robot.wheel)
        files += sorted(p for p in root.rglob("*") if p.suffix.lower() == ".dae")
    # A quarter of them are copies of another (one robot's meshes in two packages): each
    # content is read once, by its first path.
    first_of: dict[str, Path] = {}
    for path in files:
        first_of.setdefault(hashlib.sha256(path.read_bytes()).hexdigest(), path)
    return list(first_of.values())


@pytest.mark.robots
@pytest.mark.slow
def test_every_dae_of_the_description_wheels_reads_as_pycollada_reads_it(tmp_path):
    files = _wheel_dae_files(tmp_path)
    assert len(files) > 600  # different files
    mismatched, unreadable = [], set()
    for path in files:
        if "/".join(path.parts[-3:]) in NOT_XML:
            with pytest.raises(InputError, match="cannot read COLLADA file: Extra content"):
                mjcfbuild_triangles(path)
            continue
        ours = mjcfbuild_triangles(path)  # every file is read, whatever pycollada makes of it
        reference = pycollada_triangles(path)
        difference = triangle_mismatch(ours, reference.triangles)
        if difference is None:
            continue
        if reference.skipped and len(reference.triangles) == 0:
            unreadable.add("/".join(path.parts[-4:]))
        else:
            mismatched.append(f"{path}: {difference}")
    assert mismatched == []
    assert unreadable == PYCOLLADA_CANNOT_READ
