"""The binary copies of mesh products compile to the model their OBJ files compile to."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest

from mjcfbuild.meshes.convert import convert_mesh
from mjcfbuild.meshes.mshfile import copy_name, msh_bytes, read_file, text_values
from mjcfbuild.meshes.objfile import obj_bytes
from tests.conftest import EXAMPLES


def _compiled(files: list[Path], colliding: bool = True) -> mujoco.MjModel:
    """A model with one body per mesh file, each a mesh geom that collides or only draws."""
    assets = "".join(f'<mesh name="m{i}" file="{file}"/>' for i, file in enumerate(files))
    contact = "" if colliding else ' contype="0" conaffinity="0"'
    bodies = "".join(
        f'<body pos="{i} 0 0"><freejoint/><geom type="mesh" mesh="m{i}"{contact}/></body>'
        for i in range(len(files))
    )
    return mujoco.MjModel.from_xml_string(
        f"<mujoco><asset>{assets}</asset><worldbody>{bodies}</worldbody></mujoco>"
    )


def _differing_arrays(first: mujoco.MjModel, second: mujoco.MjModel) -> list[str]:
    """The names of the model arrays that differ, the file paths apart."""
    differ = []
    for name in dir(first):
        value = getattr(first, name)
        if name.startswith("_") or not isinstance(value, np.ndarray) or "path" in name:
            continue
        other = getattr(second, name)
        if value.shape != other.shape or not np.array_equal(value, other, equal_nan=True):
            differ.append(name)
    return differ


def _random_mesh(seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A closed, irregular mesh (the convex hull of random points) at a random scale and
    offset, with float64 coordinates that float32 cannot hold exactly."""
    import trimesh

    rng = np.random.default_rng(seed)
    points = rng.normal(size=(60, 3)) * rng.uniform(1e-3, 10.0, size=3)
    points += rng.uniform(-5.0, 5.0, size=3)
    hull = trimesh.Trimesh(vertices=points, process=False).convex_hull
    vertices = np.asarray(hull.vertices, dtype=np.float64)
    vertices[0, 0] = -0.0 if seed % 2 else vertices[0, 0]
    return vertices, np.asarray(hull.faces)


@pytest.mark.parametrize("seed", range(8))
def test_a_copy_compiles_to_the_model_of_its_obj_file(tmp_path, seed):
    vertices, faces = _random_mesh(seed)
    obj = tmp_path / "mesh.obj"
    obj.write_bytes(obj_bytes(text_values(vertices), faces))
    copy = tmp_path / copy_name("mesh.obj")
    copy.write_bytes(msh_bytes(vertices, faces))
    for colliding in (True, False):
        assert _differing_arrays(_compiled([obj], colliding), _compiled([copy], colliding)) == []


def test_the_obj_text_keeps_its_numbers_where_they_read_back_as_their_float32():
    """An STL file's float32 values and a text format's short decimals are written as they
    are; a value nearer the middle between two float32 values is written as its float32."""
    stl = np.array([0.1, -2.5, 1e-3], dtype=np.float32).astype(np.float64)
    assert text_values(stl).tolist() == stl.tolist()
    assert text_values(np.array([0.235, 0.0, -0.0, 12.5])).tolist() == [0.235, 0.0, -0.0, 12.5]
    below, above = np.float32(0.3), np.nextafter(np.float32(0.3), np.float32(1))
    middle = (float(below) + float(above)) / 2 - 1e-17  # rounds down, barely
    assert text_values(np.array([middle]))[0] == float(below)
    values = np.random.default_rng(1).normal(size=20000) * 10.0 ** np.arange(-4, 4).repeat(2500)
    written = np.array([float(f"{v:.9g}") for v in text_values(values)])
    assert np.array_equal(written.astype(np.float32), values.astype(np.float32))


def test_the_products_of_the_examples_compile_the_same_from_their_copies(tmp_path):
    objs, copies = [], []
    for index, source in enumerate(
        sorted(
            [
                *(EXAMPLES / "arm" / "meshes").glob("*.[sdo]*"),
                EXAMPLES / "quadruped" / "meshes" / "trunk.stl",
            ]
        )
    ):
        if source.suffix == ".mtl":
            continue
        folder = tmp_path / str(index)
        product = convert_mesh(source, folder, ["collision", "visual", "hull"])
        for name in product.files:
            if name.endswith(".obj") and read_file(name, product.files) != name:
                objs.append(folder / name)
                copies.append(folder / read_file(name, product.files))
    assert len(objs) >= 10
    assert _differing_arrays(_compiled(objs), _compiled(copies)) == []


def test_a_textured_part_is_compiled_from_its_obj_file(tmp_path):
    """An MSH file holds one texture coordinate per vertex, an OBJ file one per face corner:
    a textured part has no copy, and compiles read its OBJ file; its plain parts have one."""
    from tests.meshes import samples

    source = samples.obj_with_named_mtl_and_texture(tmp_path / "o")
    product = convert_mesh(source, tmp_path / "product", ["visual"])
    textured = [part.file for part in product.parts if part.texture]
    plain = [part.file for part in product.parts if not part.texture]
    assert textured and plain
    assert [read_file(name, product.files) for name in textured] == textured
    assert [read_file(name, product.files) for name in plain] == [copy_name(n) for n in plain]
    header = np.frombuffer((tmp_path / "product" / copy_name(plain[0])).read_bytes()[:16], "<i4")
    assert header[1:3].tolist() == [0, 0]  # no normals, no texture coordinates
