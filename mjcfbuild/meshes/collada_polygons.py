"""Triangles of COLLADA's polygons, strips and fans, as corner indices.

A polygon is fanned from its first corner where that covers it, and ear-clipped where it is
concave (as rviz's importer does); strips keep their winding triangle by triangle.
"""

from __future__ import annotations

import numpy as np


def strip_triangles(counts: np.ndarray) -> np.ndarray:
    """Triangles (as corner indices) of triangle strips; every other one is flipped so that
    all keep the strip's winding."""
    starts: np.ndarray | list[int] = (
        np.concatenate([[0], np.cumsum(counts)[:-1]]) if len(counts) else []
    )
    triangles = [
        (start + k, start + k + 1, start + k + 2)
        if k % 2 == 0
        else (start + k + 1, start + k, start + k + 2)
        for start, count in zip(list(starts), counts.tolist(), strict=True)
        for k in range(count - 2)
    ]
    return np.array(triangles, dtype=np.int64).reshape(-1, 3)


def polygon_triangles(counts: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Triangles (as corner indices) of polygons of ``counts`` corners at ``points``: a fan
    from the first corner where that covers the polygon (triangles, convex polygons), else
    ear clipping, as rviz's importer does (a fan over a concave polygon, an L-shaped face
    of a Blender n-gon, covers its notch and faces partly inward)."""
    faces = fan_triangles(counts)
    large = np.flatnonzero(counts > 3)
    if not len(large):
        return faces
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    firsts = np.concatenate([[0], np.cumsum(np.maximum(counts - 2, 0))[:-1]]).astype(np.int64)
    corners = np.flatnonzero(np.repeat(counts > 3, counts))  # those of the large polygons
    concave, normals = _concave(counts[large], points[corners])
    pieces, done = [], 0  # the fan's faces up to each concave polygon, then its clipped ones
    for polygon, normal in zip(large[concave].tolist(), normals[concave], strict=True):
        start, count, first = int(starts[polygon]), int(counts[polygon]), int(firsts[polygon])
        clipped = _ear_clipped(points[start : start + count], normal)
        if clipped is None:
            continue  # no ear clipping (a polygon crossing itself): the fan stays
        pieces += [faces[done:first], clipped + start]
        done = first + count - 2
    return np.concatenate([*pieces, faces[done:]]).astype(np.int64).reshape(-1, 3)


def _concave(counts: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per polygon (each of more than 3 corners), whether one of its corners turns against
    the polygon's winding (by more than rounding; a corner repeated next to itself left
    out): where a fan from the first corner does not cover it; and each polygon's Newell
    normal (along its winding)."""
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    owner = np.repeat(np.arange(len(counts)), counts)
    index = np.arange(len(owner))
    following = np.where(index + 1 == starts[owner] + counts[owner], starts[owner], index + 1)
    preceding = np.where(index == starts[owner], starts[owner] + counts[owner] - 1, index - 1)
    # Newell's normal of each polygon: the sum of its edges' cross products.
    normals = np.add.reduceat(np.cross(points, points[following]), starts, axis=0)
    into, out = points - points[preceding], points[following] - points
    turns = np.einsum("ij,ij->i", np.cross(into, out), normals[owner])
    sizes = np.linalg.norm(into, axis=1) * np.linalg.norm(out, axis=1)
    sizes *= np.linalg.norm(normals, axis=1)[owner]
    reflex = np.logical_or.reduceat(turns < -1e-9 * sizes, starts)
    # A corner written twice in a row hides its turn (an edge of no length): such a polygon
    # is looked at again without the repeat, one by one (they are few).
    repeated = np.flatnonzero(~reflex & np.logical_or.reduceat(~np.any(out, axis=1), starts))
    for polygon in repeated.tolist():
        ends = starts[polygon], starts[polygon] + counts[polygon]
        reflex[polygon] = _hides_a_reflex_corner(points[ends[0] : ends[1]], normals[polygon])
    return reflex, normals


def _hides_a_reflex_corner(corners: np.ndarray, normal: np.ndarray) -> bool:
    """Whether the polygon at ``corners``, a corner repeated next to itself left out, has a
    corner turning against its winding (``normal``)."""
    kept = corners[[k for k in range(len(corners)) if np.any(corners[k] != corners[k - 1])]]
    into, out = kept - np.roll(kept, 1, axis=0), np.roll(kept, -1, axis=0) - kept
    turns = np.cross(into, out) @ normal
    sizes = np.linalg.norm(into, axis=1) * np.linalg.norm(out, axis=1) * np.linalg.norm(normal)
    return bool(np.any(turns < -1e-9 * sizes))


def _ear_clipped(corners: np.ndarray, normal: np.ndarray) -> np.ndarray | None:
    """The ear-clipped triangles (corner indices) of a concave polygon with Newell normal
    ``normal``, or None where ear clipping finds no way (a polygon crossing itself). A corner
    repeated next to itself is skipped. Only reflex corners can lie in an ear, and they are
    tested together, so a polygon of thousands of corners takes a fraction of a second."""
    size = float(np.linalg.norm(normal))
    if size == 0:
        return None
    normal = normal / size
    # A basis of the plane with u x v = normal: the polygon winds counter-clockwise in it.
    other = np.eye(3)[int(np.argmin(np.abs(normal)))]
    u = np.cross(normal, other)
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    flat = np.stack([corners @ u, corners @ v], axis=1)
    flat /= max(float(np.ptp(flat, axis=0).max()), 1e-300)  # turns relative to its size
    order = [k for k in range(len(flat)) if np.any(flat[k] != flat[k - 1])]
    triangles = []
    while len(order) > 3:
        here = flat[order]
        before, after = np.roll(here, 1, axis=0), np.roll(here, -1, axis=0)
        turns = _turns(before, here, after)
        reflex = np.flatnonzero(turns <= 1e-12)
        for i in np.flatnonzero(turns > 1e-12).tolist():
            near = (i - 1) % len(order), (i + 1) % len(order)
            others = here[[k for k in reflex.tolist() if k not in near]]
            a, b, c = before[i], here[i], after[i]
            inside = (
                (_turns(a, b, others) >= 0)
                & (_turns(b, c, others) >= 0)
                & (_turns(c, a, others) >= 0)
            )
            if not inside.any():
                triangles.append((order[near[0]], order[i], order[near[1]]))
                del order[i]
                break
        else:
            return None
    triangles.append((order[0], order[1], order[2]))
    return np.array(triangles, dtype=np.int64)


def _turns(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Twice the signed areas of the triangles a b c (> 0: a left turn at b)."""
    (x1, y1), (x2, y2) = np.moveaxis(b - a, -1, 0), np.moveaxis(c - b, -1, 0)
    return x1 * y2 - y1 * x2


def fan_triangles(counts: np.ndarray) -> np.ndarray:
    """Triangles (as corner indices) fanning every polygon from its first corner."""
    if len(counts) and np.all(counts == 3):
        return np.arange(counts.sum(), dtype=np.int64).reshape(-1, 3)
    counts = np.asarray(counts, dtype=np.int64)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    per_polygon = np.maximum(counts - 2, 0)
    owner = np.repeat(np.arange(len(counts)), per_polygon)
    firsts = np.concatenate([[0], np.cumsum(per_polygon)[:-1]]).astype(np.int64)
    k = np.arange(len(owner), dtype=np.int64) - firsts[owner] + 1  # 1 .. count - 2
    start = starts[owner]
    return np.stack([start, start + k, start + k + 1], axis=1).reshape(-1, 3)
