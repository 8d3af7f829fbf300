"""The files a mesh file refers to (materials, textures, buffers), found without loading it.

They are dependencies of the mesh's conversion and part of its cache key, so they must be
known before converting: editing a ``.mtl`` or a texture rebuilds the mesh, and a cached
product is only reused when they are unchanged too.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from urllib.parse import unquote

_MTLLIB = re.compile(rb"^\s*mtllib\s+(.+?)\s*$", re.MULTILINE)
_MAP = re.compile(
    r"^\s*(?:map_\w+|bump|disp|decal|refl)\s+(?:-\S+\s+\S+\s+)*(.+?)\s*$", re.MULTILINE
)


def referenced_files(path: Path) -> list[Path]:
    """Existing files ``path`` refers to, sorted."""
    return sorted({p for _, p in _references(path) if p.is_file() and p != path})


def missing_references(path: Path) -> list[str]:
    """What ``path`` refers to that is not there (an OBJ's ``mtllib`` or a texture its
    material names, a DAE's or a glTF's image), each once as ``'name' (what it is)`` (quoted: the
    console groups warnings that differ in quoted names), sorted;
    the name is the path from the mesh's folder (``../textures/wood.png``), where the file
    was looked for, or the name of a file outside the mesh's description (an absolute
    ``file:///opt/textures/wood.png``): a path from the mesh up to the root would depend on
    the folder the description sits in."""
    missing = {(kind, p) for kind, p in _references(path) if not p.is_file()}
    return sorted({f"'{_from_folder(p, path.parent)}' ({kind})" for kind, p in missing})


# A relative path climbing this many folders is no description's own (../../materials is).
_CLIMB = 3


def _from_folder(path: Path, folder: Path) -> str:
    relative = Path(os.path.relpath(path, folder))
    if relative.parts[:_CLIMB] == ("..",) * _CLIMB:
        return path.name
    return relative.as_posix()


def missing_paths(path: Path) -> list[Path]:
    """The files of :func:`missing_references`, for a task to rerun when one appears."""
    return sorted({p for _, p in _references(path) if not p.exists()})


def _references(path: Path) -> list[tuple[str, Path]]:
    """Each file ``path`` refers to, there or not, with what it is for."""
    suffix = path.suffix.lower()
    if suffix == ".obj":
        return _obj_references(path)
    if suffix == ".dae":
        from mjcfbuild.meshes.collada import named_files

        return [("texture", p) for p in named_files(path)]
    if suffix == ".gltf":
        return _gltf_references(path)
    return []


def _obj_references(path: Path) -> list[tuple[str, Path]]:
    try:
        data = path.read_bytes()
    except OSError:
        return []
    found = []
    for match in _MTLLIB.finditer(data):
        name = match.group(1).decode("utf-8", "replace")
        library = path.parent / name
        found.append(("material library", library))
        if library.is_file():
            text = library.read_text(errors="replace")
            found += [("texture", library.parent / m.group(1)) for m in _MAP.finditer(text)]
    return found


def _gltf_references(path: Path) -> list[tuple[str, Path]]:
    try:
        document = json.loads(path.read_text())
    except (OSError, ValueError):
        return []
    found = []
    for key, kind in (("buffers", "buffer"), ("images", "image")):
        for item in document.get(key, []):
            uri = item.get("uri") if isinstance(item, dict) else None
            if uri and not uri.startswith("data:"):
                found.append((kind, path.parent / unquote(uri)))
    return found
