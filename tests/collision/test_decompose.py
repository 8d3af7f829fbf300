"""CoACD decomposition: convex parts, reproducible bytes, stable order."""

from __future__ import annotations

import numpy as np
import trimesh

from mjcfbuild.collision.decompose import decompose
from mjcfbuild.meshes.objfile import obj_bytes


def l_shape(path):
    a = trimesh.creation.box([0.4, 0.1, 0.1])
    b = trimesh.creation.box([0.1, 0.1, 0.4])
    b.apply_translation([0.15, 0, 0.25])
    mesh = trimesh.util.concatenate([a, b])
    path.write_bytes(obj_bytes(mesh.vertices, mesh.faces))
    return path


def test_non_convex_mesh_gives_several_convex_parts_reproducibly(tmp_path):
    source = l_shape(tmp_path / "l.obj")
    params = {"threshold": 0.05, "seed": 0, "preprocess_mode": "off"}
    first = decompose(source, params, tmp_path / "one")
    second = decompose(source, params, tmp_path / "two")
    assert first == second
    assert len(first["parts"]) >= 2
    for name in first["parts"]:
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "two" / name).read_bytes()
        part = trimesh.load(tmp_path / "one" / name, process=False)
        assert part.is_convex or np.isclose(part.volume, part.convex_hull.volume, rtol=1e-6)
