"""Convex decomposition, only where it pays: the hull when it is close enough, else CoACD.

For each mesh, the convex hull is measured first (:mod:`mjcfbuild.collision.concavity`). When it
stands off the mesh by no more than ``hull_tolerance`` (by default the ``threshold`` CoACD
would be asked to reach), the hull is the decomposition: one part, no CoACD. Otherwise CoACD
runs with parameters scaled to the mesh (:func:`coacd_arguments`). Either way the result is
reproducible: CoACD is seeded, parts are canonical hulls in a stable order, and the summary
says how each mesh was handled, in how many parts, how closely, and in how many seconds.
"""

from __future__ import annotations

import hashlib
import math
import time
from pathlib import Path
from typing import cast

import numpy as np

from mjcfbuild.errors import InputError
from mjcfbuild.meshes.load import at_least_min_vertices
from mjcfbuild.meshes.objfile import obj_bytes

DECOMPOSITION_FORMAT = 2
# Manifest parameter name -> CoACD keyword, where they differ.
_COACD_NAMES = {"approximate_mode": "apx_mode"}
# Decompose parameters that are mjcfbuild's own, not CoACD's.
OWN_PARAMETERS = ("hull_tolerance", "scale_to_mesh")


def decompose(mesh_file: Path, params: dict, output_dir: Path) -> dict:
    """Decompose the mesh in ``mesh_file`` into convex parts written to ``output_dir``.

    The summary lists the part files with their digests and, per mesh: ``method`` (``hull``
    or ``coacd``), ``hull_concavity`` (how far the hull stands off the mesh), ``concavity``
    (the same measure for the parts written), ``seconds`` and the CoACD arguments used.
    """
    import trimesh

    from mjcfbuild.collision.concavity import hull_concavity, parts_concavity
    from mjcfbuild.collision.primitives import spans_volume

    started = time.perf_counter()
    # trimesh.load is typed to return any Geometry; force="mesh" makes it a Trimesh
    mesh = cast(trimesh.Trimesh, trimesh.load(str(mesh_file), process=False, force="mesh"))
    if len(mesh.faces) == 0:
        raise InputError("cannot decompose a mesh without triangles", file=mesh_file)
    # One triangle (its product's extra corner is no vertex to trimesh): 4 points, which
    # qhull's first simplex needs.
    vertices, _ = at_least_min_vertices(np.asarray(mesh.vertices, dtype=np.float64), None)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    hull_error = hull_concavity(vertices, faces)
    tolerance = hull_tolerance(params)
    arguments = None
    if tolerance > 0 and hull_error <= tolerance:
        method = "hull"
        hulls = [_canonical(vertices, max_vertices=int(params.get("max_ch_vertex", 256)))]
    else:
        method = "coacd"
        arguments = coacd_arguments(params, vertices, faces)
        coacd_parts = _run_coacd(vertices, faces, arguments)
        hulls = [_canonical(np.asarray(v, dtype=np.float64)) for v, _ in coacd_parts]
    parts = [h for h in hulls if h is not None]
    if not parts and not spans_volume(vertices):
        # A flat mesh (one triangle) of which CoACD made nothing is its own hull: the
        # assembly then says in one line that it is flat, and which rule fits it.
        method = "hull"
        parts = [_canonical(vertices, keep_flat=True)]
    if not parts:
        raise InputError(
            "CoACD produced no convex parts", file=mesh_file, hint="lower the threshold"
        )
    # A stable order: by centroid, then size, so the same input always lists parts alike.
    parts.sort(key=lambda h: (*np.round(h[0].mean(axis=0), 9), len(h[0])))
    concavity = hull_error if method == "hull" else parts_concavity(vertices, faces, parts)
    output_dir.mkdir(parents=True, exist_ok=True)
    files = {}
    for index, (part_vertices, part_faces) in enumerate(parts):
        data = obj_bytes(part_vertices, part_faces)
        name = f"part{index:03d}.obj"
        (output_dir / name).write_bytes(data)
        files[name] = hashlib.md5(data, usedforsecurity=False).hexdigest()
    for stale in output_dir.iterdir():
        if stale.name not in files:
            stale.unlink()
    return {
        "format": DECOMPOSITION_FORMAT,
        "parts": sorted(files),
        "files": files,
        "method": method,
        "hull_concavity": hull_error,
        "hull_tolerance": tolerance,
        "concavity": concavity,
        "coacd": arguments,
        "seconds": round(time.perf_counter() - started, 2),
    }


def hull_tolerance(params: dict) -> float:
    """The tolerance below which the hull is kept: ``hull_tolerance``, or the threshold."""
    value = params.get("hull_tolerance")
    return float(params.get("threshold", 0.05) if value is None else value)


def coacd_arguments(params: dict, vertices: np.ndarray, faces: np.ndarray) -> dict:
    """CoACD's keyword arguments for this mesh: the manifest's, scaled to the mesh.

    With ``scale_to_mesh`` (the default), the remeshing resolution and the tree search follow
    what the threshold can resolve instead of CoACD's fixed defaults; see docs/collision.md.
    """
    arguments = {_COACD_NAMES.get(k, k): v for k, v in params.items() if k not in OWN_PARAMETERS}
    if params.get("scale_to_mesh", True):
        arguments.update(_scaled(params, vertices, faces))
    return dict(sorted(arguments.items()))


# A cheaper tree search and Hausdorff sampling than CoACD's defaults (150 iterations, 20 nodes,
# depth 3, 2000 samples). On g1's elbow, ankle pitch and hip pitch links (after the remesh
# below) 30 iterations at depth 2 took 2, 8 and 12 CPU seconds against 4, 15 and 20 at 60
# iterations, depth 3, with about as many parts (6, 39, 39) and concavities (0.07 to 0.08).
# 20 iterations took 10 to 30 % less again on eight g1 meshes (torso 24 s against 32), with
# concavities within +-0.01 and parts within about 15 % either way.
_SEARCH = {"mcts_iterations": 20, "mcts_nodes": 10, "mcts_max_depth": 2, "resolution": 1000}
# CoACD's remesh of a mesh at resolution r has about 16 r^2 triangles (measured on g1).
_REMESH_TRIANGLES_PER_CELL = 16


def _scaled(params: dict, vertices: np.ndarray, faces: np.ndarray) -> dict:
    """The parameters :func:`coacd_arguments` scales; the manifest's values are upper bounds.

    CoACD normalises a mesh to a box of side 2 and remeshes it on a grid of
    ``preprocess_resolution`` cells, so a cell is ``2 / resolution`` in the threshold's units
    and the remesh is off by up to half a cell. A resolution of ``1 / threshold`` keeps that
    error within the threshold (20 cells at 0.05, against CoACD's 50) while the work, which
    grows with the remesh's triangles, falls with its square (on g1: 6 times less CPU for
    concavities of 0.07 instead of 0.04; see README's benchmark). A mesh with more triangles
    than that remesh would have is remeshed even if it is closed, so a detailed mesh costs no
    more than a coarse one of the same shape.
    """
    threshold = float(params.get("threshold", 0.05))
    cap = int(params.get("preprocess_resolution", 50))
    resolution = max(min(20, cap), min(cap, math.ceil(1 / threshold - 1e-9)))
    scaled: dict = {"preprocess_resolution": resolution}
    scaled.update({k: min(int(params.get(k, v)), v) for k, v in _SEARCH.items()})
    heavy = len(faces) > _REMESH_TRIANGLES_PER_CELL * resolution**2
    if params.get("preprocess_mode", "auto") == "auto" and heavy:
        scaled["preprocess_mode"] = "on"
    return scaled


def _run_coacd(vertices: np.ndarray, faces: np.ndarray, arguments: dict) -> list:
    import coacd

    coacd.set_log_level("error")
    return coacd.run_coacd(coacd.Mesh(vertices, faces), **arguments)


def _canonical(vertices: np.ndarray, max_vertices: int | None = None, keep_flat: bool = False):
    """The convex hull of points with vertices and faces in a canonical order (or None).

    ``max_vertices`` keeps at most that many hull vertices, spread as far apart as possible.
    A flat hull (a triangle's two sides) is None unless ``keep_flat``.
    """
    import trimesh

    from mjcfbuild.meshes.convert import farthest_points

    if len(vertices) < 4:
        return None
    try:
        hull = trimesh.Trimesh(vertices=vertices, process=False).convex_hull
        if max_vertices is not None and len(hull.vertices) > max_vertices:
            kept = farthest_points(np.asarray(hull.vertices), max_vertices)
            hull = trimesh.Trimesh(vertices=kept, process=False).convex_hull
    except Exception:  # degenerate (flat) part
        return None
    if len(hull.faces) < 4 and not keep_flat:
        return None
    order = np.lexsort(np.round(hull.vertices, 12).T[::-1])
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    new_faces = rank[hull.faces]
    new_faces = new_faces[np.lexsort(np.sort(new_faces, axis=1).T[::-1])]
    return hull.vertices[order], new_faces
