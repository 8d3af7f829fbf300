"""Attaching normalised MJCF parts to the assembled model's MjSpec.

Each part goes into a frame named ``<prefix>attachment`` in the body that holds its ``to``
link (at the link's pose in that body, then the part's offset), through ``MjSpec.attach`` with
the part's prefix. The part's root bodies are then children of that body, so MuJoCo's
parent-child contact filter treats them as adjacent, as it does a URDF part's root.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lxml import etree

from mjcfbuild.compose.mjcf import PartSummary
from mjcfbuild.errors import ManifestError
from mjcfbuild.urdf.transforms import Transform, matrix_to_quat

# Element kinds whose names must be unique in a model, as MjSpec collections.
_NAMED = (
    "bodies",
    "joints",
    "geoms",
    "sites",
    "cameras",
    "lights",
    "meshes",
    "materials",
    "textures",
    "hfields",
    "skins",
    "tendons",
    "actuators",
    "sensors",
    "equalities",
)


# Where a link of the assembled model is: the name of the body its frame ended up in (None for
# the world body) and the frame's pose in that body (mjcf.bodies.link_places makes them).
LinkPlace = tuple[str | None, Transform]


@dataclass
class AttachedPart:
    """An MJCF part as the assembly attaches it."""

    key: str  # its place in robot.yaml, e.g. "robot.yaml attach[1]"
    prefix: str
    to: str
    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]
    xml: Path  # the normalised part
    summary: PartSummary

    @staticmethod
    def from_dict(data: dict[str, Any]) -> AttachedPart:
        """An entry of the assemble task's payload, its summary read from disk."""
        import json

        return AttachedPart(
            key=data["key"],
            prefix=data["prefix"],
            to=data["to"],
            pos=tuple(data["pos"]),
            quat=tuple(data["quat"]),
            xml=Path(data["xml"]),
            summary=PartSummary.from_dict(json.loads(Path(data["summary"]).read_text())),
        )


def attach_parts(spec, places: dict[str, LinkPlace], parts: list[AttachedPart]) -> dict[str, str]:
    """Attach ``parts`` (in order) to ``spec``, whose links are at ``places``; the asset files
    they publish, by name."""
    import mujoco

    from mjcfbuild.mjcache import forget_earlier_builds

    if parts:
        forget_earlier_builds()  # the parts' files are the user's
    published: dict[str, str] = {}
    spec.copy_during_attach = True
    for part in parts:
        child = mujoco.MjSpec.from_file(str(part.xml))
        _refuse_collisions(spec, child, part)
        target, position, quat = _place(spec, places, part)
        frame = target.add_frame(name=f"{part.prefix}attachment", pos=position, quat=quat)
        spec.attach(child, prefix=part.prefix, frame=frame)
        published.update(part.summary.assets)
    return published


def _place(spec, places: dict[str, LinkPlace], part: AttachedPart):
    """The body the part goes into, and its frame's pose there: where ``to`` is, then the
    part's offset."""
    link = None
    if part.to in places:
        body, link = places[part.to]
        target = spec.worldbody if body is None else spec.body(body)
    if link is None:
        target = spec.body(part.to)
        link = Transform()
        if target is None:
            site = spec.site(part.to)
            if site is None:  # the plan stage checked 'to'; only a stale plan gets here
                raise ManifestError(
                    f"'to' names '{part.to}', which is in the model neither as a link nor as "
                    "a body or site",
                    file=f"{part.key}.to",
                )
            target = site.parent
            link = Transform.from_quat(tuple(site.pos), tuple(site.quat))
    pose = link.compose(Transform.from_quat(part.pos, part.quat))
    return target, list(pose.position), list(matrix_to_quat(pose.rotation))


def _refuse_collisions(spec, child, part: AttachedPart) -> None:
    """A prefix that makes a name of the part equal one of the model is a manifest error."""
    for kind in _NAMED:
        existing = {element.name for element in getattr(spec, kind) if element.name}
        clashes = sorted({part.prefix + e.name for e in getattr(child, kind) if e.name} & existing)
        if clashes:
            raise ManifestError(
                f"prefix '{part.prefix}' makes the name '{clashes[0]}' ({kind}) of "
                f"{part.summary.label} collide with a name of the model",
                file=f"{part.key}.prefix",
                hint="choose a prefix no name of the model starts with",
            )


def publish_part_files(root: etree._Element, published: dict[str, str]) -> None:
    """Asset files of the parts by their published (content) names, relative to the model's
    ``assets/`` folder, so the model does not name the build's folders."""
    names = {stored: name for name, stored in published.items()}
    for tag in ("mesh", "hfield", "skin", "texture"):
        for element in root.iter(tag):
            for attribute in ("file", *_CUBE_FILES):
                value = element.get(attribute)
                if value in names:
                    element.set(attribute, names[value])


_CUBE_FILES = ("fileright", "fileleft", "fileup", "filedown", "filefront", "fileback")


def part_frames(root: etree._Element, parts: list[AttachedPart]) -> list[etree._Element]:
    """The ``<frame>`` elements holding the parts in the written model."""
    names = {f"{part.prefix}attachment" for part in parts}
    return [frame for frame in root.iter("frame") if frame.get("name") in names]
