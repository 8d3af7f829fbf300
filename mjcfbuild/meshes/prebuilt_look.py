"""The look of a pre-generated OBJ (``convert -a``) that carries none of its own.

Such an OBJ was converted from a mesh file by an earlier run, and its colour stayed with the
model that run wrote: mujoco_ros2_control's converter keeps it in obj2mjcf's ``<stem>.xml``
(whose material library a trimesh of its day named so that obj2mjcf removed it), mjcfbuild
in its ``<material>``; the OBJ alone is uncoloured. The colour is the mesh file's, so the OBJ
takes the look of the file it stands for (its geometry stays the OBJ's): the look that
file's own conversion gives it, where it has one.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from mjcfbuild.errors import InputError
from mjcfbuild.meshes.load import MeshPart, load_parts


def with_look_of(
    parts: list[MeshPart], source: Path, original: Path, warnings: list[str]
) -> list[MeshPart]:
    """``parts`` (of the pre-generated OBJ ``source``) in the look of the mesh file
    ``original``, where they have none of their own and ``original`` has one; what cannot be
    carried over (several looks, a texture) is said in ``warnings``."""
    if any(part.rgba is not None or part.texture is not None for part in parts):
        return parts  # its own material library colours it
    said = (
        f"{source.name}, the pre-generated OBJ (-a) for {original.name}, has no colour of its own"
    )
    notes: list[str] = []  # what the original's own reading loses (a glow, a blend)
    try:
        looks = load_parts(original, warnings=notes)
    except InputError as error:
        warnings.append(f"{said}, and {original.name} cannot be read for one ({error.message})")
        return parts
    distinct = {(part.rgba, part.texture.key if part.texture else None) for part in looks}
    if not looks or distinct == {(None, None)}:
        return parts  # neither is coloured (or the file shows nothing: a DAE without a scene)
    if len(distinct) > 1:
        warnings.append(
            f"{said}, and the {len(distinct)} colours of {original.name} cannot be told apart "
            "on it: the model shows it uncoloured (convert without -a to show them)"
        )
        return parts
    look = looks[0]
    warnings.extend(notes)  # the look is borrowed: what its reading lost is lost here too
    if look.texture is not None:
        warnings.append(
            f"{said}; it takes {original.name}'s colour, but not its texture, which it has no "
            "texture coordinates for (convert without -a to show it)"
        )
    return [dataclasses.replace(part, rgba=look.rgba, emission=look.emission) for part in parts]
