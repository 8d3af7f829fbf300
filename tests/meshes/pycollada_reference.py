"""Triangles of a DAE file as pycollada reads them, and as mjcfbuild does, for differential tests.

pycollada parses every float as float32 (about 1e-7 relative), so comparing at 1e-9 would only
measure its rounding: :func:`pycollada_triangles` widens its parse to float64 and otherwise
leaves its reading (id scopes, inputs, node transforms, bind shapes) as it is.
"""

from __future__ import annotations

import contextlib
import importlib
import pkgutil
import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from mjcfbuild.meshes.collada import read_collada


class _DoubleNumpy(ModuleType):
    """numpy, except that ``numpy.float32`` is float64 (pycollada names it in every parse)."""

    def __init__(self) -> None:
        super().__init__("numpy")

    def __getattr__(self, name: str) -> Any:
        return np.float64 if name == "float32" else getattr(np, name)


@contextlib.contextmanager
def _pycollada_in_double() -> Iterator[None]:
    import collada

    modules = [
        importlib.import_module(f"collada.{info.name}")
        for info in pkgutil.iter_modules(collada.__path__)
    ]
    patched = [m for m in modules if getattr(m, "numpy", None) is np]
    for module in patched:
        module.numpy = _DoubleNumpy()  # type: ignore[attr-defined]
    try:
        yield
    finally:
        for module in patched:
            module.numpy = np  # type: ignore[attr-defined]


@dataclass
class Reference:
    """pycollada's triangles (n, 3, 3) in metres, and the errors it skipped past to get them."""

    triangles: np.ndarray
    skipped: list[str]


def pycollada_triangles(path: Path) -> Reference:
    """Every surface triangle pycollada finds in the file's scene, placed by the node
    transforms and scaled by ``<unit>``. Mirroring nodes reverse the corners, as mjcfbuild
    does to keep faces facing out (pycollada keeps the written order)."""
    import collada

    with _pycollada_in_double(), warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpy.matrix and deprecations inside pycollada
        document = collada.Collada(
            str(path),
            ignore=[collada.common.DaeUnsupportedError, collada.common.DaeBrokenRefError],
        )
        unit = float(document.assetInfo.unitmeter or 1.0)
        found = []
        bound_objects = list(document.scene.objects("geometry")) if document.scene else []
        if document.scene is not None:
            bound_objects += list(document.scene.objects("controller"))
        for bound in bound_objects:
            placed = getattr(bound, "geometry", bound)  # a skin binds its geometry
            mirrored = np.linalg.det(np.asarray(placed.matrix, dtype=float)[:3, :3]) < 0
            for primitive in bound.primitives():
                if isinstance(primitive, collada.controller.BoundSkinPrimitive):
                    primitive = primitive.primitive  # the skin's geometry, bound in place
                if isinstance(primitive, collada.lineset.BoundLineSet):
                    continue  # no surface
                if not isinstance(primitive, collada.triangleset.BoundTriangleSet):
                    primitive = primitive.triangleset()
                if primitive.vertex_index is None or len(primitive.vertex_index) == 0:
                    continue
                corners = np.asarray(primitive.vertex)[np.asarray(primitive.vertex_index)]
                found.append(corners[:, ::-1] if mirrored else corners)
    triangles = np.concatenate(found) * unit if found else np.zeros((0, 3, 3))
    return Reference(triangles, [str(error) for error in document.errors])


def mjcfbuild_triangles(path: Path) -> np.ndarray:
    """Every triangle mjcfbuild's reader hands over (n, 3, 3), in metres."""
    parts = read_collada(path).parts
    if not parts:
        return np.zeros((0, 3, 3))
    return np.concatenate([part.vertices[part.faces] for part in parts])


def _canonical(triangles: np.ndarray) -> np.ndarray:
    """Triangles as rows of 9, each starting at its lowest corner (winding kept), sorted."""
    rows = np.arange(len(triangles))
    first = np.zeros(len(triangles), dtype=np.int64)
    for corner in (1, 2):
        lowest, candidate = triangles[rows, first], triangles[:, corner]
        x, y, z = (candidate[:, i] - lowest[:, i] for i in range(3))
        first[(x < 0) | ((x == 0) & ((y < 0) | ((y == 0) & (z < 0))))] = corner
    turned = triangles[rows[:, None], (first[:, None] + np.arange(3)) % 3].reshape(-1, 9)
    return turned[np.lexsort(turned.T[::-1])]


def triangle_mismatch(ours: np.ndarray, reference: np.ndarray, atol: float = 1e-9) -> str | None:
    """None when both hold the same triangles (any order, same winding) within ``atol``
    metres; otherwise what differs."""
    if ours.shape != reference.shape:
        return f"{len(ours)} triangles, pycollada {len(reference)}"
    if len(ours) == 0:
        return None
    mine, theirs = _canonical(ours), _canonical(reference)
    if np.allclose(mine, theirs, rtol=0, atol=atol):
        return None
    # Sorting can order two nearly equal triangles differently in each reading, and corners
    # that differ by rounding alone can start a triangle at different corners (rtb-data's
    # kr210l150 meshes): match every triangle to the nearest of the other reading's triangles,
    # each started at any of its corners.
    from scipy.spatial import cKDTree

    for a, b in ((mine, theirs), (theirs, mine)):
        corners = b.reshape(-1, 3, 3)
        started = np.concatenate([np.roll(corners, k, axis=1) for k in range(3)])
        distance, _ = cKDTree(started.reshape(-1, 9)).query(a)
        if distance.max() > atol * 3:
            worst = int(np.argmax(distance))
            return f"{np.sum(distance > atol * 3)} triangles differ, the worst by {distance[worst]:.3g} m"
    return None
