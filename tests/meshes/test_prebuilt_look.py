"""A pre-generated OBJ (convert -a) without a colour of its own takes the colour of the mesh
file it stands for."""

from __future__ import annotations

from mjcfbuild.meshes.load import load_parts
from mjcfbuild.meshes.prebuilt_look import with_look_of
from tests.conftest import write
from tests.meshes.test_collada_looks import coloured_dae, glowing

TETRAHEDRON = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"


def test_an_uncoloured_obj_takes_the_colour_of_its_dae(tmp_path):
    obj = write(tmp_path / "base.obj", TETRAHEDRON)
    dae = coloured_dae(tmp_path / "base.dae", "0.9 0.1 0.1")
    said: list[str] = []
    (part,) = with_look_of(load_parts(obj), obj, dae, said)
    assert part.rgba == (0.9, 0.1, 0.1, 1.0) and said == []


def test_what_the_original_s_reading_loses_is_said_when_its_look_is_taken(tmp_path):
    """A glow MuJoCo cannot show: said when the DAE is converted, and (it was not) when an
    OBJ of it takes its look under -a, whose model loses the glow the same way."""
    obj = write(tmp_path / "glow.obj", TETRAHEDRON)
    said: list[str] = []
    (part,) = with_look_of(load_parts(obj), obj, glowing(tmp_path, "0 0 0.5"), said)
    assert part.rgba == (0.8, 0.4, 0.0, 1.0) and part.emission is None
    (warning,) = said
    assert warning.startswith("glow.dae: material 'mat' glows 0 0 0.5 (<emission>)")


def test_an_obj_coloured_by_its_own_material_library_keeps_its_colour(tmp_path):
    write(tmp_path / "own.mtl", "newmtl m\nKd 0 0 1\n")
    obj = write(tmp_path / "base.obj", "mtllib own.mtl\nusemtl m\n" + TETRAHEDRON)
    dae = coloured_dae(tmp_path / "base.dae", "0.9 0.1 0.1")
    (part,) = with_look_of(load_parts(obj), obj, dae, [])
    assert part.rgba == (0.0, 0.0, 1.0, 1.0)


def test_colours_the_obj_cannot_tell_apart_are_said(tmp_path):
    obj = write(tmp_path / "base.obj", TETRAHEDRON)
    write(tmp_path / "looks.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n")
    original = write(
        tmp_path / "two.obj",
        "mtllib looks.mtl\nusemtl a\n"
        + TETRAHEDRON
        + "usemtl b\nv 2 0 0\nv 3 0 0\nv 2 1 0\nv 2 0 1\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n",
    )
    said: list[str] = []
    (part,) = with_look_of(load_parts(obj), obj, original, said)
    assert part.rgba is None
    assert said == [
        "base.obj, the pre-generated OBJ (-a) for two.obj, has no colour of its own, and the 2 "
        "colours of two.obj cannot be told apart on it: the model shows it uncoloured (convert "
        "without -a to show them)"
    ]


def test_a_file_that_shows_nothing_leaves_the_obj_as_it_is(tmp_path):
    from tests.meshes.test_collada import MATERIAL, QUAD, dae

    obj = write(tmp_path / "base.obj", TETRAHEDRON)
    loose = write(
        tmp_path / "base.dae", dae(QUAD + MATERIAL.format(diffuse="<color>1 0 0 1</color>"))
    )
    said: list[str] = []
    (part,) = with_look_of(load_parts(obj), obj, loose, said)
    assert part.rgba is None and said == []
