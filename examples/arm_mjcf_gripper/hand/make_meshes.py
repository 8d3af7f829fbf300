"""Generate the meshes of the example MJCF hand: a palm and a finger, as binary STL.

The example ships these generated files so it builds without running this script; a test
checks that they are exactly what this script writes. Run it from anywhere:

    python examples/arm_mjcf_gripper/hand/make_meshes.py
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np
import trimesh

ASSETS = Path(__file__).resolve().parent / "assets"


def binary_stl(mesh: trimesh.Trimesh) -> bytes:
    """A binary STL file of ``mesh`` (fixed header, so the bytes are reproducible)."""
    header = b"mjcfbuild example hand".ljust(80, b" ")
    triangles = mesh.vertices[mesh.faces].astype(np.float32)
    normals = mesh.face_normals.astype(np.float32)
    records = bytearray()
    for normal, triangle in zip(normals, triangles, strict=True):
        records += struct.pack("<12fH", *normal, *triangle.reshape(-1), 0)
    return header + struct.pack("<I", len(triangles)) + bytes(records)


def meshes() -> dict[str, bytes]:
    """Every generated file, by name."""
    flange = trimesh.creation.cylinder(radius=0.035, height=0.01, sections=32)
    flange.apply_translation([0, 0, 0.005])
    body = trimesh.creation.box(extents=[0.04, 0.1, 0.03])
    body.apply_translation([0, 0, 0.025])
    palm = trimesh.util.concatenate([flange, body])
    finger = trimesh.creation.box(extents=[0.02, 0.012, 0.045])
    finger.apply_translation([0, 0.006, 0.0225])
    return {"palm.stl": binary_stl(palm), "finger.stl": binary_stl(finger)}


def main() -> None:
    """Write the meshes into examples/arm_mjcf_gripper/hand/assets."""
    ASSETS.mkdir(exist_ok=True)
    for name, data in meshes().items():
        (ASSETS / name).write_bytes(data)
        print(f"wrote {ASSETS / name} ({len(data)} bytes)")


if __name__ == "__main__":
    main()
