"""The best-fitting box, capsule, cylinder or sphere around a set of points.

"Best" is the smallest volume that still encloses every point, so no contact is missed.
Cylinders and capsules are tried along the axes of the oriented bounding box and the principal
axes of the points; their cross-section is the smallest circle around the projected points.
Points that span no volume (a flat plate, a rod) are first given a thickness of
:data:`FLAT_THICKNESS` of their span (twice their farthest point from their mean) across what
they lack, so a plate gets a thin box (a disc a thin cylinder) rather than a zero-width shape
that collides with nothing and holds no mass.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# The thickness given to points that span no volume, as a fraction of their span.
FLAT_THICKNESS = 0.01


@dataclass
class Primitive:
    """A MuJoCo primitive: type, MJCF size, and pose (4x4) relative to the points' frame."""

    kind: str
    size: tuple[float, ...]
    transform: np.ndarray
    volume: float


def fit_primitive(points: np.ndarray, kinds: tuple[str, ...] | None = None) -> Primitive:
    """The smallest of the enclosing box, sphere, cylinders and capsules of ``points``
    (only those of ``kinds``, when given)."""
    import trimesh

    points = _thickened(np.asarray(points, dtype=np.float64))
    candidates = []

    to_origin, extents = trimesh.bounds.oriented_bounds(points)
    box_transform = np.linalg.inv(to_origin)
    extents = np.maximum(extents, 1e-6)
    candidates.append(Primitive("box", tuple(extents / 2), box_transform, float(np.prod(extents))))

    center, radius = _ball(points)
    sphere = np.eye(4)
    sphere[:3, 3] = center
    candidates.append(Primitive("sphere", (radius,), sphere, 4.0 / 3.0 * math.pi * radius**3))

    centred = points - points.mean(axis=0)
    _, _, principal = np.linalg.svd(centred, full_matrices=False)
    axes = [box_transform[:3, i] for i in range(3)] + [principal[i] for i in range(3)]
    for axis in axes:
        frame = _frame_with_z(axis)
        candidates.append(_cylinder_along(points, frame))
        candidates.append(_capsule_along(points, frame))
    if kinds is not None:
        candidates = [c for c in candidates if c.kind in kinds]
    return min(candidates, key=lambda p: (round(p.volume, 15), p.kind))


def _frame_with_z(axis: np.ndarray) -> np.ndarray:
    """A rotation whose third column is ``axis`` (normalised)."""
    z = axis / np.linalg.norm(axis)
    helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def spans_volume(points: np.ndarray) -> bool:
    """Whether ``points`` span a volume (not a plane, a line or a point), as every fit and
    MuJoCo's convex hull need; the one rule for a flat mesh."""
    points = np.asarray(points, dtype=np.float64)
    if len(points) < 4:
        return False
    spread = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    return _rank(spread) == 3


def _rank(spread: np.ndarray) -> int:
    """How many dimensions points span, from their singular values (relative to the largest)."""
    if spread.size == 0 or spread[0] <= 0:
        return 0
    return int(np.sum(spread > spread[0] * 1e-9))


def _thickened(points: np.ndarray) -> np.ndarray:
    """``points``, or where they span less than a volume (a plane, a line, one point) the points
    moved both ways by half of :data:`FLAT_THICKNESS` of their span along each direction they
    lack, so every fit has a volume to enclose (qhull refuses flat input)."""
    mean = points.mean(axis=0)
    _, spread, principal = np.linalg.svd(points - mean, full_matrices=False)
    rank = _rank(spread)
    if rank == 3:
        return points
    if rank == 0:
        thickness, spanned = 2e-6, np.eye(3)[:0]
    else:
        # Their span as twice the farthest point from their mean: the same whichever way the
        # in-plane axes fall (a square plate's are any two, and its extent along them was
        # anything between its side and its diagonal).
        extent = 2.0 * float(np.linalg.norm(points - mean, axis=1).max())
        thickness, spanned = max(extent * FLAT_THICKNESS, 2e-6), principal[:rank]
    lacking = _complement(spanned)
    grown = points
    for direction in lacking:
        offset = direction * thickness / 2
        grown = np.concatenate([grown + offset, grown - offset])
    return grown


def _complement(spanned: np.ndarray) -> np.ndarray:
    """Unit vectors (rows) orthogonal to the rows of ``spanned`` and to each other, making 3."""
    _, _, vt = np.linalg.svd(np.vstack([spanned, np.zeros((3, 3))]))
    return vt[len(spanned) :]


def _ball(points: np.ndarray) -> tuple[np.ndarray, float]:
    """The smallest ball (circle, for 2-D points) around ``points``, also where they span fewer
    dimensions than they have: qhull then refuses them, so it is given only the ones spanned."""
    import trimesh

    mean = points.mean(axis=0)
    _, spread, principal = np.linalg.svd(points - mean, full_matrices=False)
    rank = _rank(spread)
    if rank == 0:
        return mean, 1e-6
    if rank == points.shape[1]:
        center, radius = trimesh.nsphere.minimum_nsphere(points)
        return np.asarray(center, dtype=np.float64), max(float(radius), 1e-6)
    basis = principal[:rank]
    reduced = (points - mean) @ basis.T
    if rank == 1:
        low, high = float(reduced.min()), float(reduced.max())
        center, radius = np.array([(low + high) / 2]), (high - low) / 2
    else:
        center, radius = trimesh.nsphere.minimum_nsphere(reduced)
    return mean + np.asarray(center, dtype=np.float64) @ basis, max(float(radius), 1e-6)


def _circle(points_2d: np.ndarray) -> tuple[np.ndarray, float]:
    return _ball(points_2d)


def _cylinder_along(points: np.ndarray, rotation: np.ndarray) -> Primitive:
    local = points @ rotation
    center, radius = _circle(local[:, :2])
    low, high = float(local[:, 2].min()), float(local[:, 2].max())
    half = max((high - low) / 2, 1e-6)
    transform = np.eye(4)
    transform[:3, :3] = rotation
    transform[:3, 3] = rotation @ np.array([center[0], center[1], (high + low) / 2])
    return Primitive("cylinder", (radius, half), transform, math.pi * radius**2 * 2 * half)


def _capsule_along(points: np.ndarray, rotation: np.ndarray) -> Primitive:
    local = points @ rotation
    center, radius = _circle(local[:, :2])
    radial = np.hypot(local[:, 0] - center[0], local[:, 1] - center[1])
    cap = np.sqrt(np.maximum(radius**2 - radial**2, 0.0))
    top = float(np.max(local[:, 2] - cap))
    bottom = float(np.min(local[:, 2] + cap))
    half = max((top - bottom) / 2, 1e-6)
    transform = np.eye(4)
    transform[:3, :3] = rotation
    transform[:3, 3] = rotation @ np.array([center[0], center[1], (top + bottom) / 2])
    volume = math.pi * radius**2 * 2 * half + 4.0 / 3.0 * math.pi * radius**3
    return Primitive("capsule", (radius, half), transform, volume)
