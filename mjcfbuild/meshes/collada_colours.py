"""Per-vertex colours (``<input semantic="COLOR">``) as a MuJoCo model can show them.

A MuJoCo mesh has no colour per vertex: its geom's material colours it whole. So faces are
coloured one by one, each with the mean of its corners' colours, and grouped by colour into
parts, a geom each; past :data:`MOST_COLOURS` colours a file's faces take their average
instead (a scanned mesh's thousands of shades would be thousands of geoms). Alpha is left out:
exporters write 0 there for opaque colours (MeshLab's iCub meshes), and viewers that draw
vertex colours draw them opaque.
"""

from __future__ import annotations

import numpy as np

RGBA = tuple[float, float, float, float]

# The most colours a file's vertex colours become parts of (as for a PLY's face colours).
MOST_COLOURS = 16


def face_colours(corner_rgb: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, bool]:
    """Each face's colour (the mean of its corners', RGB in 0-1, rounded as colours are
    elsewhere), and whether some face's corners differ (a blend the model cannot show)."""
    corners = np.clip(corner_rgb[faces], 0.0, 1.0)  # (faces, 3 corners, 3 channels)
    blended = bool(np.any(corners != corners[:, :1]))
    return np.round(corners.mean(axis=1), 6), blended


def by_colour(colours: np.ndarray) -> list[tuple[RGBA, np.ndarray]]:
    """The faces (as indices) of each colour in ``colours``, in order of first appearance."""
    distinct, first, inverse = np.unique(colours, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    return [
        (_rgba(distinct[k]), np.flatnonzero(inverse == k)) for k in np.argsort(first, kind="stable")
    ]


def average(colours: list[RGBA], weights: list[int]) -> RGBA:
    """The mean of ``colours``, each counted ``weights`` times (its faces)."""
    mean = np.average(np.asarray(colours, dtype=np.float64), axis=0, weights=weights)
    return _rgba(np.round(mean[:3], 6))


def _rgba(rgb: np.ndarray) -> RGBA:
    r, g, b = (float(v) for v in rgb[:3])
    return (r, g, b, 1.0)
