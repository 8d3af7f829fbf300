"""Reading mesh files into parts by colour."""

from __future__ import annotations

import numpy as np
import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.meshes.load import MeshPart, load_parts, merge_vertices
from tests.conftest import EXAMPLES, write


def test_stl_has_one_uncoloured_part_with_shared_vertices():
    (part,) = load_parts(EXAMPLES / "arm" / "meshes" / "base.stl")
    assert part.rgba is None
    assert len(part.faces) == 128
    assert len(part.vertices) == 66  # STL repeats corners; they are shared again


def test_obj_materials_come_from_its_own_mtl_file_whatever_its_name():
    parts = load_parts(EXAMPLES / "arm" / "meshes" / "forearm.obj")
    colours = sorted(tuple(round(c, 2) for c in p.rgba) for p in parts)
    assert colours == [(0.1, 0.3, 0.8, 1.0), (0.85, 0.85, 0.88, 1.0)]


def test_dae_colour():
    (part,) = load_parts(EXAMPLES / "arm" / "meshes" / "upper_arm.dae")
    assert part.rgba == pytest.approx((0.9, 0.45, 0.1, 1.0), abs=0.01)


def test_broken_and_empty_files_are_input_errors(tmp_path):
    with pytest.raises(InputError) as info:
        load_parts(write(tmp_path / "bad.dae", "<COLLADA><broken"))
    assert info.value.location.file.endswith("bad.dae")
    with pytest.raises(InputError):
        load_parts(write(tmp_path / "empty.obj", "# nothing\n"))


def test_merge_vertices_keeps_first_appearance_order():
    vertices = np.array([[1, 0, 0], [0, 0, 0], [1, 0, 0], [-0.0, 0, 0], [0, 1, 0]], dtype=float)
    faces = np.array([[0, 1, 4], [2, 3, 4]])
    merged = merge_vertices(MeshPart(vertices, faces, None))
    assert merged.vertices.tolist() == [[1, 0, 0], [0, 0, 0], [0, 1, 0]]
    assert merged.faces.tolist() == [[0, 1, 2], [0, 1, 2]]


def test_merge_vertices_tells_apart_vertices_whose_hashes_collide():
    """Vertices are grouped by a hash of their bits; two different ones with the same hash
    stay two vertices (grouped by their bytes instead)."""
    multiplier = np.uint64(0x9E3779B97F4A7C15)
    first = np.array([1.0, 2.0, 3.0]).view(np.uint64)
    other = first.copy()
    other[0] = np.array([1.5]).view(np.uint64)[0]
    # the same hash: ((x * m) ^ y) * m ^ z equal when (x * m) ^ y is (arrays: wrapping)
    other[1:2] = (first[0:1] * multiplier) ^ first[1:2] ^ (other[0:1] * multiplier)
    assert ((first[0:1] * multiplier) ^ first[1:2]) == ((other[0:1] * multiplier) ^ other[1:2])
    vertices = np.vstack([first, other, first, [0, 0, 0]]).astype(np.uint64).view(np.float64)
    assert np.isfinite(vertices).all() and not np.array_equal(vertices[0], vertices[1])
    merged = merge_vertices(MeshPart(vertices, np.array([[0, 1, 3], [2, 1, 3]]), None))
    assert len(merged.vertices) == 3
    assert merged.faces.tolist() == [[0, 1, 2], [0, 1, 2]]
    assert merged.vertices[1].tobytes() == vertices[1].tobytes()


def test_merge_vertices_keeps_texture_seams_and_drops_unused_vertices():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 0], [5, 5, 5]], dtype=float)
    uv = np.array([[0, 0], [1, 0], [0, 1], [0.5, 0.5], [0, 0]], dtype=float)
    faces = np.array([[0, 1, 2], [3, 1, 2]])
    merged = merge_vertices(MeshPart(vertices, faces, None, uv))
    assert len(merged.vertices) == 4  # (0,0,0) twice: different texture coordinates
    assert merged.uv.tolist()[3] == [0.5, 0.5]


CUBE_CORNERS = "".join(f"v {x} {y} {z}\n" for x in (0, 1) for y in (0, 1) for z in (0, 1))


@pytest.mark.parametrize(
    ("text", "line", "says"),
    [
        ("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", 2, "a vertex with 2 coordinates"),
        (CUBE_CORNERS + "f 1 2 3\nf 1 2 99\n", 10, "a face names vertex 99; 8 come before it"),
        ("\ufeff" + CUBE_CORNERS + "f 1 2 3\n", 1, "the file starts with a byte-order mark"),
    ],
    ids=["two-coordinates", "missing-vertex", "byte-order-mark"],
)
def test_an_obj_that_breaks_its_indexing_is_an_error_at_its_line(tmp_path, text, line, says):
    """trimesh read these without a word or with numpy's words; the conversion then failed
    as an internal error or named no line."""
    path = write(tmp_path / "m.obj", text)
    with pytest.raises(InputError) as info:
        load_parts(path)
    assert says in str(info.value) and info.value.location.line == line


@pytest.mark.parametrize(
    ("cut", "says"),
    [(-384, "but the file has 300 bytes: it is cut short"), (9, "it has 9 bytes after its end")],
    ids=["cut-short", "bytes-after"],
)
def test_a_binary_stl_whose_length_is_not_its_count_says_so(tmp_path, cut, says):
    """Read as ASCII, such a file had "no triangles": the wrong thing to look for."""
    whole = b"\0" * 80 + (12).to_bytes(4, "little") + b"\0" * (50 * 12)
    path = tmp_path / "m.stl"
    path.write_bytes(whole[:cut] if cut < 0 else whole + b"\0" * cut)
    with pytest.raises(InputError) as info:
        load_parts(path)
    assert "binary STL declares 12 triangles (684 bytes)" in str(info.value)
    assert says in str(info.value)


def test_a_coordinate_no_robot_reaches_is_refused_by_its_size(tmp_path):
    """A damaged file's 1e30 reached MuJoCo, which called the vertices "collinear"."""
    path = write(tmp_path / "m.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n")
    with pytest.raises(InputError) as info:
        load_parts(path)
    assert "mesh has a vertex coordinate of 1e+30, farther than any robot reaches" in str(
        info.value
    )


def test_bytes_that_are_no_stl_are_called_so_not_a_cut_binary(tmp_path):
    path = tmp_path / "m.stl"
    path.write_bytes(b"\x8f" * 5000)  # bytes 80-83 read as 2.4 billion triangles
    with pytest.raises(InputError) as info:
        load_parts(path)
    assert str(info.value).startswith("not an STL file: it is not ASCII STL")
    assert "does not fit its 5000 bytes" in str(info.value)


@pytest.mark.parametrize(
    "text",
    [
        "v 0 0 0\nf 1 1 1\n",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",  # collinear
    ],
    ids=["one-point", "collinear"],
)
def test_a_mesh_whose_every_triangle_is_degenerate_is_refused_at_its_file(tmp_path, text):
    """MuJoCo refused the product instead, naming mjcfbuild's copy of it."""
    path = write(tmp_path / "m.obj", text)
    with pytest.raises(InputError) as info:
        load_parts(path)
    assert "every triangle of the mesh is degenerate (no area)" in str(info.value)
    assert info.value.location.file == str(path)


@pytest.mark.parametrize(
    ("name", "text", "line", "says"),
    [
        (
            "m.stl",
            "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0\n"
            "   vertex 0 1 0\n  endloop\n endfacet\nendsolid x\n",
            5,
            "a vertex with 2 coordinates (it has 3)",
        ),
        ("m.obj", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", 2, "vertex coordinate 'x' is not"),
    ],
    ids=["ascii-stl-two-coordinates", "obj-word-for-a-number"],
)
def test_a_text_mesh_trimesh_cannot_read_is_an_error_at_its_line(tmp_path, name, text, line, says):
    """trimesh's own words named no line ("incorrect number of vertices")."""
    path = write(tmp_path / name, text)
    with pytest.raises(InputError) as info:
        load_parts(path)
    assert says in str(info.value) and info.value.location.line == line


def test_a_dae_texture_that_is_no_image_is_left_out_with_a_warning(tmp_path):
    """bullet-safety-gym's kinect.dae names kinect.tga, which is a web page: the build stopped
    ("cannot read texture image") where a missing texture only warns."""
    from tests.meshes.test_collada import INSTANCE, MATERIAL, QUAD, dae, scene

    write(tmp_path / "skin.png", "<html>not found</html>")
    body = QUAD + MATERIAL.format(diffuse='<texture texture="samp" texcoord="UV"/>')
    path = write(tmp_path / "q.dae", dae(body, scene=scene(f"<node>{INSTANCE}</node>")))
    warnings: list[str] = []
    (part,) = load_parts(path, warnings=warnings)
    assert part.texture is None and len(part.faces) == 2
    assert warnings == [
        "q.dae: its texture skin.png is no image mjcfbuild can read; the model shows the mesh "
        "without it (re-save the texture as PNG or JPEG)"
    ]


def test_a_short_text_file_named_stl_is_said_to_be_no_stl(tmp_path):
    text = tmp_path / "arm.stl"
    text.write_text("This is not a valid STL file.\n")  # before: "mesh has no triangles"
    with pytest.raises(InputError, match="not an STL file: it is not ASCII STL") as refused:
        load_parts(text)
    assert "too short for binary STL (84 bytes at least)" in refused.value.message
    empty_ascii = tmp_path / "empty.stl"
    empty_ascii.write_text("solid a\nendsolid a\n")  # an STL file, without triangles
    with pytest.raises(InputError, match="mesh has no triangles"):
        load_parts(empty_ascii)


CUBE_OBJ = """mtllib cube.mtl
v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 1 0 1\nv 1 1 0\nv 1 1 1
v 2 0 0\nv 2 1 0\nv 2 0 1
usemtl blue
f 1 2 4\nf 1 4 3\nf 5 7 8\nf 5 8 6\nf 1 5 6\nf 1 6 2\nf 3 4 8\nf 3 8 7\nf 1 3 7\nf 1 7 5
f 2 6 8\nf 2 8 4
usemtl red
f 9 10 11
"""
CUBE_MTL = "newmtl blue\nKd 0 0 1\nnewmtl red\nKd 1 0 0\nnewmtl orange\nKd 1 0.5 0\n"


def compiles_in_mujoco(parts: list[MeshPart]) -> bool:
    """Whether MuJoCo takes every part as a mesh of its own (it refuses one of < 4 vertices)."""
    import mujoco

    spec = mujoco.MjSpec()
    for index, part in enumerate(parts):
        mesh = spec.add_mesh(name=f"part{index}")
        mesh.uservert = part.vertices.ravel().tolist()
        mesh.userface = part.faces.ravel().tolist()
        body = spec.worldbody.add_body()
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"part{index}")
    spec.compile()
    return True


def test_a_look_on_fewer_than_four_vertices_takes_the_nearest_colour_with_a_warning(tmp_path):
    """One red triangle beside a blue cube: a part of 3 vertices, which MuJoCo refuses, so
    the model would not load (vertex-coloured DAE files made many such parts). The triangle
    is drawn in the cube's blue, with a warning; a mesh of small looks only takes their mean."""
    write(tmp_path / "cube.mtl", CUBE_MTL)
    path = write(tmp_path / "cube.obj", CUBE_OBJ)
    warnings: list[str] = []
    (part,) = load_parts(path, warnings=warnings)
    assert part.rgba == (0.0, 0.0, 1.0, 1.0) and len(part.faces) == 13
    assert warnings == [
        "cube.obj: 1 of its looks (colours or materials) cover fewer than 4 vertices, a mesh "
        "too small for MuJoCo: each is drawn in the look nearest in colour"
    ]
    assert compiles_in_mujoco([part])
    # Two single triangles, red and orange: nothing large to fold into; their mean colour.
    two = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl red\nf 1 2 3\nusemtl orange\nf 1 2 4\n"
    path = write(tmp_path / "two.obj", "mtllib cube.mtl\n" + two)
    (part,) = load_parts(path, warnings=[])
    assert part.rgba == pytest.approx((1.0, 0.25, 0.0, 1.0), abs=0.01) and len(part.vertices) == 4
    assert compiles_in_mujoco([part])
