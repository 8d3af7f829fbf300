"""Which mesh files mjcfbuild reads."""

from __future__ import annotations

from pathlib import Path

MESH_FORMATS = {
    ".stl": "STL",
    ".obj": "OBJ",
    ".dae": "COLLADA",
    ".glb": "glTF binary",
    ".gltf": "glTF",
    ".ply": "PLY",
}


def mesh_format(path: str | Path) -> str | None:
    """The lower-case extension of a supported mesh file, or None."""
    suffix = Path(path).suffix.lower()
    return suffix if suffix in MESH_FORMATS else None
