"""Generate the meshes of the example quadruped: a trunk, a thigh and a shin, as binary STL.

The example ships these generated files so it builds without running this script; a test
checks that they are exactly what this script writes. Run it from anywhere:

    python examples/quadruped/make_meshes.py
"""

from __future__ import annotations

from pathlib import Path

import trimesh

MESHES = Path(__file__).resolve().parent / "meshes"


def meshes() -> dict[str, bytes]:
    """File name -> STL bytes of every mesh of the example (metres, Z up, link frames)."""
    trunk = trimesh.creation.box(extents=(0.42, 0.2, 0.1))
    thigh = trimesh.creation.capsule(height=0.16, radius=0.022, count=(12, 12))
    thigh.apply_translation((0, 0, -0.1))
    shin = trimesh.creation.capsule(height=0.17, radius=0.016, count=(12, 12))
    shin.apply_translation((0, 0, -0.1))
    return {
        "trunk.stl": trunk.export(file_type="stl"),
        "thigh.stl": thigh.export(file_type="stl"),
        "shin.stl": shin.export(file_type="stl"),
    }


if __name__ == "__main__":
    MESHES.mkdir(exist_ok=True)
    for name, data in meshes().items():
        (MESHES / name).write_bytes(data)
        print(f"wrote {MESHES / name}")
