"""Converting one mesh file into the OBJ files a model uses (a mesh *product*).

A product is a folder of OBJ files and a summary: one OBJ per material for drawing, and, when
the mesh also serves as collision geometry, one OBJ of all its triangles (MuJoCo collides with
its convex hull). A mesh with a single material uses the same file for both.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from mjcfbuild.fsutil import write_if_changed
from mjcfbuild.meshes.load import load_parts
from mjcfbuild.meshes.objfile import obj_bytes

PRODUCT_FORMAT = 1


def convert_mesh(source: Path, product_dir: Path, roles: list[str]) -> dict:
    """Write the product of ``source`` into ``product_dir`` and return its summary.

    File names inside a product do not depend on what the mesh is called in a robot, so the
    same input gives the same product wherever it is used; the assembly names the published
    asset files.
    """
    import numpy as np

    parts = load_parts(source)
    product_dir.mkdir(parents=True, exist_ok=True)
    files: dict[str, str] = {}

    def store(name: str, data: bytes) -> str:
        write_if_changed(product_dir / name, data)
        files[name] = hashlib.md5(data, usedforsecurity=False).hexdigest()
        return name

    summary_parts = []
    if len(parts) == 1:
        part = parts[0]
        name = store("mesh.obj", obj_bytes(part.vertices, part.faces))
        summary_parts.append(_part_summary(name, part))
        collision = name if "collision" in roles else None
    else:
        for index, part in enumerate(parts):
            name = store(f"part{index}.obj", obj_bytes(part.vertices, part.faces))
            summary_parts.append(_part_summary(name, part))
        collision = None
        if "collision" in roles:
            offset = 0
            all_vertices, all_faces = [], []
            for part in parts:
                all_vertices.append(part.vertices)
                all_faces.append(part.faces + offset)
                offset += len(part.vertices)
            collision = store(
                "collision.obj", obj_bytes(np.concatenate(all_vertices), np.concatenate(all_faces))
            )
    for stale in product_dir.iterdir():
        if stale.name not in files:
            stale.unlink()
    return {
        "format": PRODUCT_FORMAT,
        "parts": summary_parts,
        "collision": collision,
        "files": dict(sorted(files.items())),
    }


def _part_summary(name: str, part) -> dict:
    return {
        "file": name,
        "rgba": list(part.rgba) if part.rgba is not None else None,
        "vertices": len(part.vertices),
        "faces": len(part.faces),
    }
