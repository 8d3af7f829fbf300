"""Mesh files of an exported URDF: one OBJ (with its MTL) per mesh and colour.

URDF gives a visual one colour, and many tools show a mesh's own material rather than the
URDF's, so each mesh is written once per colour it is drawn in, with that colour in its MTL.
Collision geometry reuses a mesh's first file (colour does not matter there).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from mjcfbuild.export.model import RGBA, MeshOut
from mjcfbuild.export.stamp import STAMP

# The first line of every OBJ and MTL file written: a later export may replace them.
STAMP_LINE = f"# {STAMP}\n".encode("ascii")
_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def colour_key(rgba: RGBA) -> str:
    """Eight hex digits naming a colour (rounded to 8 bits a channel)."""
    return "".join(f"{round(max(0.0, min(1.0, v)) * 255):02x}" for v in rgba)


def colour_text(values) -> str:
    """Colour channels as text: 6 digits, which is what MuJoCo's float32 colours hold."""
    return " ".join(f"{float(v):.6g}" for v in values)


def safe_stem(name: str) -> str:
    """A file name made of letters, digits, '_', '-' and '.', never hidden or empty."""
    stem = _UNSAFE.sub("_", name).lstrip(".")
    return stem or "mesh"


@dataclass
class MeshFiles:
    """Chooses file names for (mesh, colour) pairs and produces their bytes."""

    meshes: dict[int, MeshOut]
    uses: dict[int, list[str]] = field(default_factory=dict)
    colours: dict[str, RGBA] = field(default_factory=dict)

    def add_shape(self, name: str, vertices, faces) -> int:
        """Add a mesh made here (an ellipsoid) under a new id, reusing an identical one."""
        for index, mesh in self.meshes.items():
            if index < 0 and mesh.name == name and _same(mesh, vertices, faces):
                return index
        index = min([0, *self.meshes]) - 1
        self.meshes[index] = MeshOut(name, vertices, faces)
        return index

    def colour(self, rgba: RGBA) -> str:
        """Register a colour the URDF uses; its key."""
        key = colour_key(rgba)
        self.colours.setdefault(key, rgba)
        return key

    def use(self, mesh: int, rgba: RGBA | None) -> None:
        """Record that ``mesh`` is drawn in ``rgba`` (None: used for collision only)."""
        keys = self.uses.setdefault(mesh, [])
        if rgba is not None:
            key = self.colour(rgba)
            if key not in keys:
                keys.append(key)

    def stems(self) -> dict[tuple[int, str | None], str]:
        """File stem of every (mesh, colour key) pair, and of (mesh, None) for collisions."""
        result: dict[tuple[int, str | None], str] = {}
        taken: set[str] = set()
        # Meshes of the model first, in their order, then the shapes made here.
        for mesh in sorted(self.uses, key=lambda m: (m < 0, abs(m))):
            base = safe_stem(self.meshes[mesh].name)
            keys = self.uses[mesh]
            wanted = [(key, base if len(keys) == 1 else f"{base}_{key}") for key in keys]
            fallback: list[tuple[str | None, str]] = [(None, base)]
            for key, stem in wanted or fallback:
                unique, number = stem, 2
                while unique.lower() in taken:
                    unique, number = f"{stem}_{number}", number + 1
                taken.add(unique.lower())
                result[(mesh, key)] = unique
            result.setdefault((mesh, None), result[(mesh, keys[0])] if keys else base)
        return result

    def files(self) -> dict[str, bytes]:
        """Every file to write, by name: ``<stem>.obj`` and, for drawn meshes, ``<stem>.mtl``."""
        from mjcfbuild.meshes.objfile import obj_bytes

        result: dict[str, bytes] = {}
        for (mesh, key), stem in sorted(self.stems().items(), key=lambda item: item[1]):
            if f"{stem}.obj" in result:
                continue
            data = self.meshes[mesh]
            body = obj_bytes(data.vertices, data.faces)
            if key is None:
                result[f"{stem}.obj"] = STAMP_LINE + body
                continue
            header = f"mtllib {stem}.mtl\nusemtl {stem}\n".encode("ascii")
            result[f"{stem}.obj"] = STAMP_LINE + header + body
            result[f"{stem}.mtl"] = STAMP_LINE + _mtl(stem, self.colours[key])
        return result


def _mtl(name: str, rgba: RGBA) -> bytes:
    diffuse, alpha = colour_text(rgba[:3]), colour_text(rgba[3:])
    return f"newmtl {name}\nKa 0 0 0\nKd {diffuse}\nKs 0 0 0\nd {alpha}\n".encode("ascii")


def _same(mesh: MeshOut, vertices, faces) -> bool:
    import numpy as np

    return np.array_equal(mesh.vertices, vertices) and np.array_equal(mesh.faces, faces)
