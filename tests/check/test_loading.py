"""The check and previews read a built model's assets from the products they were published
from, but only where the bytes are the same."""

from __future__ import annotations

import json
from pathlib import Path

import mujoco
import numpy as np

import mjcfbuild
from mjcfbuild.check.loading import (
    COPIES_KEY,
    SOURCES_KEY,
    AssetSource,
    asset_sources,
    collision_files,
    compile_model,
    source_entries,
    spec_reading_sources,
    warm_meshes,
)
from tests.conftest import write

TETRAHEDRON = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
PRISM = TETRAHEDRON.replace("f 1 3 2", "v 1 1 1\nf 1 3 2\nf 2 5 3") + "f 3 5 4\nf 2 4 5\n"


def published_model(folder: Path) -> tuple[Path, Path]:
    """A model naming ``assets/part.obj`` and the product it was published from."""
    model = write(
        folder / "model.xml",
        '<mujoco><compiler meshdir="assets"/><asset><mesh name="part" file="part.obj"/>'
        '</asset><worldbody><body><freejoint/><geom type="mesh" mesh="part"/></body>'
        "</worldbody></mujoco>",
    )
    write(folder / "assets" / "part.obj", TETRAHEDRON)
    product = write(folder / ".mjcfbuild" / "products" / "part" / "mesh.obj", TETRAHEDRON)
    return model, product


def test_an_identical_asset_is_read_from_its_product(tmp_path):
    model, product = published_model(tmp_path)
    spec = spec_reading_sources(model, {"part.obj": AssetSource(product)})
    assert spec.meshes[0].file == str(product)
    built = compile_model(model, {"part.obj": AssetSource(product)})
    plain = mujoco.MjModel.from_xml_path(str(model))
    assert built.mesh_vertnum.tolist() == plain.mesh_vertnum.tolist() == [4]


def test_an_asset_that_differs_from_its_product_is_read_as_published(tmp_path):
    model, product = published_model(tmp_path)
    (tmp_path / "assets" / "part.obj").write_text(PRISM)  # edited after the build
    sources = {"part.obj": AssetSource(product)}
    assert spec_reading_sources(model, sources).meshes[0].file == "part.obj"
    assert compile_model(model, sources).mesh_vertnum.tolist() == [5]
    product.unlink()  # and a product gone since is no source either
    assert compile_model(model, sources).mesh_vertnum.tolist() == [5]


def test_an_identical_asset_is_read_from_its_products_copy_while_that_is_intact(tmp_path):
    import hashlib

    from mjcfbuild.meshes.mshfile import msh_bytes

    model, product = published_model(tmp_path)
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    data = msh_bytes(vertices, faces)
    copy = product.with_suffix(".msh")
    copy.write_bytes(data)
    md5 = hashlib.md5(data, usedforsecurity=False).hexdigest()
    sources = {"part.obj": AssetSource(product, copy, md5)}
    assert spec_reading_sources(model, sources).meshes[0].file == str(copy)
    assert compile_model(model, sources).mesh_vertnum.tolist() == [4]
    # A copy that is not what the build wrote (a conversion stopped between the two files)
    # is not read: the product is.
    copy.write_bytes(msh_bytes(vertices * 2, faces))
    assert spec_reading_sources(model, sources).meshes[0].file == str(product)
    copy.unlink()
    assert spec_reading_sources(model, sources).meshes[0].file == str(product)


def test_the_sources_record_is_relative_and_optional(tmp_path):
    report = tmp_path / "state" / "assembly.json"
    product = tmp_path / "state" / "products" / "part" / "mesh.obj"
    entries = source_entries({"part.obj": str(product)}, report.parent)
    assert entries == {"part.obj": "products/part/mesh.obj"}
    write(report, json.dumps({SOURCES_KEY: entries}))
    product = report.parent / "products/part/mesh.obj"
    assert asset_sources(report) == {"part.obj": AssetSource(product)}
    copies = {"part.obj": ["products/part/mesh.msh", "0123"]}
    write(report, json.dumps({SOURCES_KEY: entries, COPIES_KEY: copies}))
    copy = report.parent / "products/part/mesh.msh"
    assert asset_sources(report) == {"part.obj": AssetSource(product, copy, "0123")}
    assert asset_sources(report)["part.obj"].read == copy
    write(report, "{}")  # a report written before the record existed
    assert asset_sources(report) == {}
    assert asset_sources(tmp_path / "missing.json") == {}
    assert asset_sources(None) == {}


def test_warming_skips_files_mujoco_rejects(tmp_path):
    broken = write(tmp_path / "broken.obj", "this is not a mesh\n")
    warm_meshes([str(broken), str(write(tmp_path / "notes.txt", "no mesh"))])  # no error


def _product(folder: Path, name: str, collision: str | None) -> str:
    """A mesh product ``name`` whose summary says whether collision geoms use its mesh."""
    mesh = write(folder / "products" / name / "mesh.obj", PRISM)
    summary = {
        "format": 2,
        "parts": [],
        "collision": collision,
        "collision_volume": 0.0,
        "hull": None,
        "faces": 4,
        "files": {},
        "warnings": [],
    }
    write(folder / "products" / f"{name}.json", json.dumps(summary))
    return str(mesh)


def test_warming_gives_the_meshes_collision_geoms_use_their_hull(tmp_path):
    """MuJoCo keeps a file's first processing: one without the hull a collision geom needs
    would be processed again by every compile of the model, and never cached."""
    drawn = _product(tmp_path, "drawn", None)
    colliding = _product(tmp_path, "colliding", "mesh.obj")
    part = str(write(tmp_path / "decompositions" / "x" / "part000.obj", TETRAHEDRON))
    assert collision_files([drawn, colliding, part]) == {colliding, part}
    cache = mujoco.mj_getCache()
    sizes = []
    for file in (drawn, colliding):
        mujoco.mj_clearCache(cache)
        warm_meshes([file])
        sizes.append(mujoco.mj_getCacheSize(cache))
    mujoco.mj_clearCache(cache)
    assert 0 < sizes[0] < sizes[1]  # the same mesh, with its hull


def test_a_build_records_the_product_of_every_asset(tmp_path, monkeypatch):
    from tests.conftest import copy_example

    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    folder = copy_example("arm", tmp_path)
    result = mjcfbuild.build(folder / "robot.yaml", jobs=1, check=False)
    assert result.ok
    output = result.robot.parent
    sources = asset_sources(output / ".mjcfbuild" / "assembly.json")
    assets = sorted(path.name for path in (output / "assets").iterdir())
    assert sorted(sources) == assets
    for asset, source in sources.items():
        assert source.product.read_bytes() == (output / "assets" / asset).read_bytes()
    # the meshes without texture coordinates are read from their products' binary copies
    copied = sorted(name for name, source in sources.items() if source.copy)
    assert copied == sorted(name for name in assets if name.endswith(".obj"))
    published = compile_model(result.robot)
    from_copies = compile_model(result.robot, sources)
    assert published.mesh_vert.tobytes() == from_copies.mesh_vert.tobytes()
    assert published.mesh_face.tobytes() == from_copies.mesh_face.tobytes()
