"""Generate the meshes of the example arm: STL, COLLADA (DAE) and OBJ with two materials.

The example ships these generated files so it builds without running this script; a test
checks that they are exactly what this script writes. Run it from anywhere:

    python examples/arm/make_meshes.py
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np
import trimesh

MESHES = Path(__file__).resolve().parent / "meshes"


def binary_stl(mesh: trimesh.Trimesh) -> bytes:
    """A binary STL file of ``mesh`` (fixed header, so the bytes are reproducible)."""
    header = b"mjcfbuild example arm".ljust(80, b" ")
    triangles = mesh.vertices[mesh.faces].astype(np.float32)
    normals = mesh.face_normals.astype(np.float32)
    records = bytearray()
    for normal, triangle in zip(normals, triangles, strict=True):
        records += struct.pack("<12fH", *normal, *triangle.reshape(-1), 0)
    return header + struct.pack("<I", len(triangles)) + bytes(records)


def obj_with_materials(pieces: list[tuple[str, trimesh.Trimesh]], mtl_name: str) -> bytes:
    """An OBJ file whose pieces use the named materials of ``mtl_name``."""
    lines = [f"mtllib {mtl_name}"]
    offset = 1
    for material, mesh in pieces:
        lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in mesh.vertices]
        lines.append(f"usemtl {material}")
        lines += [f"f {a + offset} {b + offset} {c + offset}" for a, b, c in mesh.faces]
        offset += len(mesh.vertices)
    return ("\n".join(lines) + "\n").encode()


def collada(mesh: trimesh.Trimesh, rgba: tuple[float, float, float, float]) -> bytes:
    """A minimal COLLADA 1.4 file: one triangle mesh, one coloured material, Z up, metres."""
    positions = " ".join(f"{v:.6f}" for v in mesh.vertices.reshape(-1))
    indices = " ".join(str(i) for i in mesh.faces.reshape(-1))
    colour = " ".join(f"{c:g}" for c in rgba)
    text = f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_effects>
    <effect id="paint-effect"><profile_COMMON><technique sid="common"><phong>
      <diffuse><color>{colour}</color></diffuse>
    </phong></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials>
    <material id="paint" name="paint"><instance_effect url="#paint-effect"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="shape" name="shape"><mesh>
      <source id="shape-positions">
        <float_array id="shape-positions-array" count="{mesh.vertices.size}">
          {positions}
        </float_array>
        <technique_common>
          <accessor source="#shape-positions-array" count="{len(mesh.vertices)}" stride="3">
            <param name="X" type="float"/><param name="Y" type="float"/>
            <param name="Z" type="float"/>
          </accessor>
        </technique_common>
      </source>
      <vertices id="shape-vertices">
        <input semantic="POSITION" source="#shape-positions"/>
      </vertices>
      <triangles material="paint" count="{len(mesh.faces)}">
        <input semantic="VERTEX" source="#shape-vertices" offset="0"/>
        <p>{indices}</p>
      </triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene"><node id="part" name="part">
      <instance_geometry url="#shape"><bind_material><technique_common>
        <instance_material symbol="paint" target="#paint"/>
      </technique_common></bind_material></instance_geometry>
    </node></visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"""
    return text.encode()


def meshes() -> dict[str, bytes]:
    """Every generated file, by name."""
    base = trimesh.creation.cylinder(radius=0.08, height=0.1, sections=32)
    base.apply_translation([0, 0, 0.05])
    upper = trimesh.creation.capsule(height=0.3, radius=0.045, count=[16, 8])
    upper.apply_translation([0, 0, 0.15])
    forearm_body = trimesh.creation.box(extents=[0.06, 0.06, 0.24])
    forearm_body.apply_translation([0, 0, 0.12])
    forearm_band = trimesh.creation.cylinder(radius=0.04, height=0.03, sections=24)
    forearm_band.apply_translation([0, 0, 0.25])
    finger = trimesh.creation.box(extents=[0.015, 0.01, 0.05])
    finger.apply_translation([0, 0.005, 0.025])
    return {
        "base.stl": binary_stl(base),
        "upper_arm.dae": collada(upper, (0.9, 0.45, 0.1, 1.0)),
        "forearm.obj": obj_with_materials(
            [("shell", forearm_body), ("band", forearm_band)], "forearm_colours.mtl"
        ),
        "forearm_colours.mtl": (
            b"newmtl shell\nKd 0.85 0.85 0.88\nd 1\n\nnewmtl band\nKd 0.1 0.3 0.8\nd 1\n"
        ),
        "finger.stl": binary_stl(finger),
    }


def main() -> None:
    """Write the meshes into examples/arm/meshes."""
    MESHES.mkdir(exist_ok=True)
    for name, data in meshes().items():
        (MESHES / name).write_bytes(data)
        print(f"wrote {MESHES / name} ({len(data)} bytes)")


if __name__ == "__main__":
    main()
