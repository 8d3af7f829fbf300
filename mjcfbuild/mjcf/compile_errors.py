"""MuJoCo's compile errors about a prepared URDF, as one line that names the description's
file, line and mesh (MuJoCo names its own asset names and the prepared file)."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from mjcfbuild.errors import ModelError
from mjcfbuild.mjcf.prepared import MeshAsset, Prepared

if TYPE_CHECKING:
    from mjcfbuild.mjcf.bodies import Body
    from mjcfbuild.urdf.model import Robot

# What to do about the MuJoCo compile errors a URDF can cause, by a phrase of their message.
_COMPILE_HINTS = {
    "free joint can only be used on top level": (
        "MuJoCo allows a floating joint only from the world: from the root link, or a link "
        "fixed to it with options.fuse_static on; else make it fixed or another kind"
    ),
    "repeated in equality constraint": "a joint cannot <mimic> itself",
    "mesh surface area is too small": (
        "MuJoCo ignores each triangle under about 5e-16 m^2 and needs more area than 1e-15: "
        "check the mesh's unit and its <mesh scale>, or remove the geometry that names it"
    ),
    "coplanar vertices": (
        "a robot.yaml collision rule {meshes: [<its file name>], policy: primitive} gives it a "
        "thin box, policy: none no contact"
    ),
}


def compile_error(exc: Exception, source: str, meshes: list[MeshAsset] | None = None) -> ModelError:
    """A MuJoCo compile error as one line, pointing at the URDF line in the element's info
    (or at the URDF itself when MuJoCo names no element). A mesh MuJoCo names by its internal
    asset name (``mesh4``) is named by its file and URDF line from ``meshes``."""
    text = str(exc).strip().replace("Error: ", "", 1)
    lines = text.splitlines()
    message = lines[0] if lines else "compile failed"
    hint = next((h for phrase, h in _COMPILE_HINTS.items() if phrase in message), None)
    asset = _named_mesh(message, meshes or [])
    if asset is not None:
        named = f"mesh '{asset.uri or asset.file}'"
        message = message.replace(f"mesh '{asset.name}'", named)
        message = _TOO_SMALL.sub(lambda m: f"{m.group(1)}: {named}", message)
        if asset.line is not None:
            return ModelError(f"MuJoCo: {message}", file=source, line=asset.line, hint=hint)
    for line in lines[1:]:
        if "Element" in line and ", " in line:
            origin = line.split(", ")[-1]
            if ":" in origin and not origin.startswith("id "):
                file, _, rest = origin.partition(":")
                number, _, what = rest.partition(" ")
                if number.isdigit():
                    return ModelError(
                        f"MuJoCo: {message} ({what.strip()})",
                        file=file,
                        line=int(number),
                        hint=hint,
                    )
            message = f"{message} ({line.strip()})"
    return ModelError(f"MuJoCo: {message}", file=source, hint=hint)


def spec_meshes(spec, prepared: Prepared) -> list[MeshAsset]:
    """The prepared mesh assets under the names MuJoCo's URDF import gave them (``mesh4``),
    matched by file, so that its errors can name the description's file."""
    from dataclasses import replace

    by_file = {asset.read_file: asset for asset in prepared.meshes}
    named = []
    for mesh in spec.meshes:
        asset = by_file.get(mesh.file)
        if asset is not None:
            named.append(replace(asset, name=mesh.name))
    return named


# MuJoCo names a mesh after "too small" without quotes: "mesh surface area is too small: mesh4"
_TOO_SMALL = re.compile(r"(mesh (?:surface area|volume) is too small): (\S+)")


def _named_mesh(message: str, meshes: list[MeshAsset]) -> MeshAsset | None:
    """The mesh asset a MuJoCo message names (``mesh 'mesh4' ...``, ``... is too small:
    mesh4``), if one."""
    small = _TOO_SMALL.search(message)
    for asset in meshes:
        if f"mesh '{asset.name}'" in message or (small and small.group(2) == asset.name):
            return asset
    return None


def too_thin_mesh(text: str) -> str | None:
    """The mesh a MuJoCo 'mesh volume is too small' error names, if it is one."""
    marker = "mesh volume is too small: "
    if marker not in text:
        return None
    return text.split(marker, 1)[1].split(" ", 1)[0].split("\n", 1)[0].strip(" .")


def body_error(message: str, error: str, robot: Robot, bodies: list[Body]) -> ModelError | None:
    """MuJoCo's ``error`` about the mass or inertia of a body the URDF's links make (``Element
    name 'base', id 1``) as one line at the URDF line of the first of its links' ``<inertial>``,
    naming the links fused into that body; None for any other error."""
    # MuJoCo names the failing element (a body, joint, actuator, ...) by its name alone, and a
    # URDF joint may share a link's name: only a mass or inertia error is surely a body's.
    if "mass" not in message and "inertia" not in message:
        return None
    named = re.search(r"Element name '([^']*)', id \d+", error)
    body = next((b for b in bodies if named and b.name == named.group(1)), None)
    if body is None:
        return None
    by_name = {link.name: link for link in robot.links}
    links = [by_name[frame.link] for frame in body.links if frame.link in by_name]
    if not links:
        return None
    with_mass = [link for link in links if link.inertial is not None]
    first = (with_mass or links)[0]
    line = first.inertial.line if first.inertial else first.line
    fused = [link.name for link in links if link is not links[0]]
    together = f" (links {', '.join([links[0].name, *fused])} fused into it)" if fused else ""
    return ModelError(
        f"MuJoCo rejected body '{body.name}'{together}: {message}",
        file=robot.source,
        line=line,
        hint="check the <inertial> of these links: their mass, inertia and origin",
    )
