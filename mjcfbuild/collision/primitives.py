"""The best-fitting box, capsule, cylinder or sphere around a set of points.

"Best" is the smallest volume that still encloses every point, so no contact is missed.
Cylinders and capsules are tried along the axes of the oriented bounding box and the principal
axes of the points; their cross-section is the smallest circle around the projected points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


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

    points = np.asarray(points, dtype=np.float64)
    candidates = []

    to_origin, extents = trimesh.bounds.oriented_bounds(points)
    box_transform = np.linalg.inv(to_origin)
    extents = np.maximum(extents, 1e-6)
    candidates.append(Primitive("box", tuple(extents / 2), box_transform, float(np.prod(extents))))

    center, radius = trimesh.nsphere.minimum_nsphere(points)
    sphere = np.eye(4)
    sphere[:3, 3] = center
    radius = max(float(radius), 1e-6)
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


def _circle(points_2d: np.ndarray) -> tuple[np.ndarray, float]:
    import trimesh

    center, radius = trimesh.nsphere.minimum_nsphere(points_2d)
    return np.asarray(center, dtype=np.float64), max(float(radius), 1e-6)


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
