"""The files a mesh file refers to (materials, textures, buffers), found without loading it.

They are dependencies of the mesh's conversion and part of its cache key, so they must be
known before converting: editing a ``.mtl`` or a texture rebuilds the mesh, and a cached
product is only reused when they are unchanged too.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from urllib.parse import unquote

_MTLLIB = re.compile(rb"^\s*mtllib\s+(.+?)\s*$", re.MULTILINE)
_MAP = re.compile(
    r"^\s*(?:map_\w+|bump|disp|decal|refl)\s+(?:-\S+\s+\S+\s+)*(.+?)\s*$", re.MULTILINE
)


def referenced_files(path: Path) -> list[Path]:
    """Existing files ``path`` refers to, sorted."""
    suffix = path.suffix.lower()
    if suffix == ".obj":
        found = _obj_references(path)
    elif suffix == ".dae":
        from mjcfbuild.meshes.collada import referenced_files as collada_references

        found = collada_references(path)
    elif suffix == ".gltf":
        found = _gltf_references(path)
    else:
        found = []
    return sorted({p for p in found if p.is_file() and p != path})


def _obj_references(path: Path) -> list[Path]:
    try:
        data = path.read_bytes()
    except OSError:
        return []
    found = []
    for match in _MTLLIB.finditer(data):
        name = match.group(1).decode("utf-8", "replace")
        library = path.parent / name
        if not library.is_file():
            continue
        found.append(library)
        text = library.read_text(errors="replace")
        found += [library.parent / m.group(1) for m in _MAP.finditer(text)]
    return found


def _gltf_references(path: Path) -> list[Path]:
    try:
        document = json.loads(path.read_text())
    except (OSError, ValueError):
        return []
    found = []
    for item in document.get("buffers", []) + document.get("images", []):
        uri = item.get("uri") if isinstance(item, dict) else None
        if uri and not uri.startswith("data:"):
            found.append(path.parent / unquote(uri))
    return found
