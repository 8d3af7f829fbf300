"""Reading a mesh file of any supported format into triangle parts, one per material."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mjcfbuild.errors import InputError


@dataclass
class MeshPart:
    """Triangles that share one material, in the file's own frame and units (metres)."""

    vertices: np.ndarray
    faces: np.ndarray
    rgba: tuple[float, float, float, float] | None


def load_parts(path: Path) -> list[MeshPart]:
    """The triangles of ``path`` grouped by colour, in a stable order.

    Node transforms inside the file (DAE, glTF scene graphs) are applied. Parts come in order
    of first appearance in the file, so the same file always gives the same parts.
    """
    import trimesh

    try:
        scene = trimesh.load(str(path), force="scene", process=False)
    except Exception as exc:  # trimesh raises many kinds for broken files
        raise InputError(
            f"cannot read mesh: {_first_line(exc)}",
            file=path,
            hint="open it in a mesh tool to check it; re-export it if it is damaged",
        ) from None
    geometries = [g for g in scene.dump(concatenate=False) if isinstance(g, trimesh.Trimesh)]
    groups: dict[tuple | None, list[trimesh.Trimesh]] = {}
    for geometry in geometries:
        if len(geometry.faces) == 0:
            continue
        for colour, piece in _split_by_colour(geometry):
            groups.setdefault(colour, []).append(piece)
    if not groups:
        raise InputError("mesh has no triangles", file=path, hint="re-export it with its faces")
    parts = []
    for colour, pieces in groups.items():
        vertices, faces = _concatenate(pieces)
        if not np.all(np.isfinite(vertices)):
            raise InputError("mesh has vertices that are not finite numbers", file=path)
        parts.append(MeshPart(*merge_vertices(vertices, faces), colour))
    return parts


def merge_vertices(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Share vertices with exactly equal positions, keeping first-appearance order.

    Mesh files often repeat a vertex for every face corner (STL always does, DAE for its
    normals); sharing them makes files several times smaller and faster for MuJoCo to load.
    """
    rows = np.ascontiguousarray(vertices + 0.0)  # + 0.0 so -0.0 and 0.0 are the same vertex
    keys = rows.view(np.dtype((np.void, rows.dtype.itemsize * 3))).ravel()
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    # Renumber so vertices keep the order in which the file first used them.
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return rows[first[order]], rank[inverse.ravel()][faces]


def _first_line(exc: Exception) -> str:
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def _concatenate(pieces: list) -> tuple[np.ndarray, np.ndarray]:
    vertices = []
    faces = []
    offset = 0
    for piece in pieces:
        vertices.append(np.asarray(piece.vertices, dtype=np.float64))
        faces.append(np.asarray(piece.faces, dtype=np.int64) + offset)
        offset += len(piece.vertices)
    return np.concatenate(vertices), np.concatenate(faces)


def _split_by_colour(geometry) -> list[tuple[tuple | None, object]]:
    """The geometry as (colour, piece) pairs; colour None when the file gives none."""
    visual = geometry.visual
    kind = getattr(visual, "kind", None)
    if kind == "texture" or hasattr(visual, "material"):
        return [(_material_colour(getattr(visual, "material", None)), geometry)]
    if kind in ("face", "vertex") and getattr(visual, "defined", False):
        face_colours = np.asarray(visual.face_colors)
        distinct = np.unique(face_colours, axis=0)
        if len(distinct) == 1:
            return [(_rgba255(distinct[0]), geometry)]
        if len(distinct) <= 16:
            pieces = []
            for colour in _in_order_of_appearance(face_colours):
                mask = np.all(face_colours == colour, axis=1)
                pieces.append(
                    (_rgba255(colour), geometry.submesh([np.nonzero(mask)[0]], append=True))
                )
            return pieces
        return [(_rgba255(face_colours.mean(axis=0)), geometry)]
    return [(None, geometry)]


def _in_order_of_appearance(colours: np.ndarray) -> list[np.ndarray]:
    _, first = np.unique(colours, axis=0, return_index=True)
    return [colours[i] for i in sorted(first)]


def _rgba255(values) -> tuple[float, float, float, float]:
    rgba = [float(v) / 255.0 for v in values][:4]
    while len(rgba) < 4:
        rgba.append(1.0)
    return tuple(round(v, 6) for v in rgba)


def _material_colour(material) -> tuple[float, float, float, float] | None:
    if material is None:
        return None
    base = getattr(material, "baseColorFactor", None)
    if base is not None:
        return (
            _rgba255(base)
            if np.asarray(base).dtype == np.uint8
            else tuple(round(float(v), 6) for v in base)
        )
    diffuse = getattr(material, "diffuse", None)
    if diffuse is not None:
        return _rgba255(diffuse)
    main = getattr(material, "main_color", None)
    return _rgba255(main) if main is not None else None
