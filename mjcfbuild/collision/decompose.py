"""Convex decomposition with CoACD, reproducible: seeded, parts in a stable order."""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import cast

import numpy as np

from mjcfbuild.errors import InputError
from mjcfbuild.meshes.objfile import obj_bytes

DECOMPOSITION_FORMAT = 1
# Manifest parameter name -> CoACD keyword, where they differ.
_COACD_NAMES = {"approximate_mode": "apx_mode"}


def decompose(mesh_file: Path, params: dict, output_dir: Path) -> dict:
    """Decompose the mesh in ``mesh_file`` into convex parts written to ``output_dir``."""
    import coacd
    import trimesh

    coacd.set_log_level("error")
    # trimesh.load is typed to return any Geometry; force="mesh" makes it a Trimesh
    mesh = cast(trimesh.Trimesh, trimesh.load(str(mesh_file), process=False, force="mesh"))
    if len(mesh.faces) == 0:
        raise InputError("cannot decompose a mesh without triangles", file=mesh_file)
    arguments = {_COACD_NAMES.get(k, k): v for k, v in params.items()}
    parts = coacd.run_coacd(
        coacd.Mesh(np.asarray(mesh.vertices), np.asarray(mesh.faces)), **arguments
    )
    hulls = [
        _canonical(np.asarray(v, dtype=np.float64), np.asarray(f, dtype=np.int64)) for v, f in parts
    ]
    hulls = [h for h in hulls if h is not None]
    if not hulls:
        raise InputError(
            "CoACD produced no convex parts", file=mesh_file, hint="lower the threshold"
        )
    # A stable order: by centroid, then size, so the same input always lists parts alike.
    hulls.sort(key=lambda h: (*np.round(h[0].mean(axis=0), 9), len(h[0])))
    output_dir.mkdir(parents=True, exist_ok=True)
    files = {}
    for index, (vertices, faces) in enumerate(hulls):
        data = obj_bytes(vertices, faces)
        name = f"part{index:03d}.obj"
        (output_dir / name).write_bytes(data)
        files[name] = hashlib.md5(data, usedforsecurity=False).hexdigest()
    for stale in output_dir.iterdir():
        if stale.name not in files:
            stale.unlink()
    return {"format": DECOMPOSITION_FORMAT, "parts": sorted(files), "files": files}


def _canonical(vertices: np.ndarray, faces: np.ndarray):
    """The convex hull of a part with vertices and faces in a canonical order (or None)."""
    import trimesh

    if len(vertices) < 4:
        return None
    try:
        hull = trimesh.Trimesh(vertices=vertices, process=False).convex_hull
    except Exception:  # degenerate (flat) part
        return None
    if len(hull.faces) < 4:
        return None
    order = np.lexsort(np.round(hull.vertices, 12).T[::-1])
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    new_faces = rank[hull.faces]
    new_faces = new_faces[np.lexsort(np.sort(new_faces, axis=1).T[::-1])]
    return hull.vertices[order], new_faces
