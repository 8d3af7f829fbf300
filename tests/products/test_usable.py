"""A product is usable only if every file its summary names is there and matches."""

from __future__ import annotations

import hashlib

import pytest

from mjcfbuild.products.usable import product_problem


def files(folder, **contents: str) -> dict[str, str]:
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in contents.items():
        (folder / name.replace("_", ".")).write_text(text)
    return {
        name.replace("_", "."): hashlib.md5(text.encode(), usedforsecurity=False).hexdigest()
        for name, text in contents.items()
    }


def mesh_summary(listed: dict[str, str], **fields) -> dict:
    part = {"file": "mesh.obj", "rgba": None, "texture": None, "vertices": 3, "faces": 1}
    summary = {
        "format": 2,
        "parts": [{**part, "volume": 0.0}],
        "collision": "mesh.obj",
        "collision_volume": 0.0,
        "hull": None,
        "faces": 1,
        "files": listed,
        "warnings": [],
    }
    return {**summary, **fields}


def test_a_complete_mesh_product_is_usable(tmp_path):
    listed = files(tmp_path, mesh_obj="v 0 0 0\n")
    assert product_problem("mesh", mesh_summary(listed), tmp_path) is None


@pytest.mark.parametrize(
    ("change", "problem"),
    [
        ({"collision": "ghost.obj"}, "names ghost.obj, which it does not contain"),
        ({"hull": "hull.obj"}, "names hull.obj"),
        ({"parts": "not a list"}, "cannot be read"),
        ({"files": {"../mesh.obj": "0" * 32}}, "unsafe file"),
        ({"files": {"mesh.obj": "0" * 32}}, "mesh.obj does not match its digest"),
    ],
)
def test_unusable_mesh_products(tmp_path, change, problem):
    listed = files(tmp_path, mesh_obj="v 0 0 0\n")
    found = product_problem("mesh", mesh_summary(listed, **change), tmp_path)
    assert found is not None and problem in found


def test_a_texture_a_part_names_must_be_there(tmp_path):
    listed = files(tmp_path, mesh_obj="v 0 0 0\n")
    summary = mesh_summary(listed)
    summary["parts"][0]["texture"] = "skin.png"
    assert "names skin.png" in product_problem("mesh", summary, tmp_path)


def test_decompositions_and_matrices(tmp_path):
    listed = files(tmp_path, part000_obj="v 0 0 0\n")
    assert (
        product_problem("decompose", {"parts": ["part000.obj"], "files": listed}, tmp_path) is None
    )
    assert "names part001.obj" in product_problem(
        "decompose", {"parts": ["part000.obj", "part001.obj"], "files": listed}, tmp_path
    )
    assert "cannot be read" in product_problem(
        "decompose", {"parts": [], "files": listed}, tmp_path
    )
    assert "names matrix.json" in product_problem("selfcollision", {"files": listed}, tmp_path)


def test_a_listed_file_that_is_gone(tmp_path):
    listed = files(tmp_path, mesh_obj="v 0 0 0\n")
    (tmp_path / "mesh.obj").unlink()
    assert product_problem(None, {"files": listed}, tmp_path) == "mesh.obj is missing"
    assert "cannot be read" in product_problem(None, None, tmp_path)
