"""Joining URDF parts to a main URDF: names prefixed, file references kept valid, a fixed joint.

The result is one URDF the rest of the build treats like any other, so meshes, collision
policies, inertia repair, actuators, the self-collision matrix and the check cover every part,
and robot.yaml rules name the parts' links and joints with their prefix.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from mjcfbuild.errors import InputError, ManifestError
from mjcfbuild.sources.packages import did_you_mean

# Top-level URDF elements a part keeps; the others (mujoco, mujoco_inputs, and a <gazebo>
# without a reference: plugins of the part's own simulation) are left out, with a warning.
# A <gazebo reference> (the sensors on a link) and a URDF <sensor> are kept, their names and
# the link or joint they are on prefixed, so the plan reads them as the main source's.
_KEPT = ("link", "joint", "material", "transmission", "ros2_control", "gazebo", "sensor")


def _kept(element: etree._Element) -> bool:
    if not isinstance(element.tag, str) or element.tag not in _KEPT:
        return False
    return element.tag != "gazebo" or bool((element.get("reference") or "").strip())


@dataclass
class Part:
    """One expanded part and how it is attached."""

    xml: bytes
    label: str  # the part's file, as messages show it
    key: str  # its place in robot.yaml, e.g. "robot.yaml attach[0]"
    prefix: str
    to: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]
    resolve: Callable[[str], Path]  # a file reference of the part -> an absolute path


_ORIGIN = "mjcfbuild-origin"  # while joining: which input (0 main, n part n) and line


def compose(
    main: bytes,
    main_label: str,
    parts: list[Part],
    base_dir: Path,
    origins: dict[int, tuple[int, int]] | None = None,
) -> tuple[bytes, list[str]]:
    """The main URDF with every part joined to it, and warnings.

    File references of the parts become paths relative to ``base_dir`` (the main source's
    folder, against which the plan resolves relative paths). Parts are joined in the order
    their ``to`` links exist, so a part may attach to another part's link. ``origins``, if
    given, receives for each line of the result whose element came from an input the input
    (0 the main URDF, n the n-th part) and its line there.
    """
    warnings: list[str] = []
    root = _parse(main, main_label, warnings)
    _mark(root, 0)
    pending = list(parts)
    while pending:
        links = _names(root, "link")
        ready = [part for part in pending if part.to in links]
        if not ready:
            raise _unplaceable(pending, links)
        for part in ready:
            warnings += _join(root, part, base_dir, parts.index(part) + 1)
            pending.remove(part)
    marks = []
    for element in root.iter():
        if isinstance(element.tag, str):
            marks.append(element.attrib.pop(_ORIGIN, ""))
    text = etree.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"
    if origins is not None:
        lines = [e.sourceline for e in _parse(text, main_label).iter() if isinstance(e.tag, str)]
        for line, mark in zip(lines, marks, strict=True):
            if mark and line is not None:
                source, _, written = mark.partition(":")
                origins.setdefault(line, (int(source), int(written)))
    return text, warnings


def _mark(tree: etree._Element, source: int) -> None:
    """Tag every element of ``tree`` with the input it comes from and its line there."""
    for element in tree.iter():
        if isinstance(element.tag, str) and element.sourceline is not None:
            element.set(_ORIGIN, f"{source}:{element.sourceline}")


def _parse(data: bytes, label: str, warnings: list[str] | None = None) -> etree._Element:
    """The root of a URDF read as the plan reads one (as MuJoCo's parser reads what libxml2
    alone would refuse, with a warning in ``warnings``), its comments kept."""
    from mjcfbuild.urdf.parse import parse_xml

    root = parse_xml(data, label, [] if warnings is None else warnings, keep_comments=True)
    if root.tag != "robot":
        raise InputError(f"the root element is <{root.tag}>, not <robot>", file=label)
    return root


def _names(root: etree._Element, tag: str) -> list[str]:
    return [element.get("name", "") for element in root.findall(tag)]


def _unplaceable(pending: list[Part], links: list[str]) -> ManifestError:
    """Why none of ``pending`` can be joined: an unknown link, or parts attached to each other."""
    from mjcfbuild.compose.chain import stuck_chain
    from mjcfbuild.sources.packages import listing

    owner = {
        part.prefix + name: part
        for part in pending
        for name in _names(_parse(part.xml, part.label), "link")
    }
    last, cycle = stuck_chain(pending[0], owner, lambda part: part.to)
    if cycle is None:
        return ManifestError(
            f"'to' names link '{last.to}', which is not a link of the model"
            f"{did_you_mean(last.to, set(links))}",
            file=f"{last.key}.to",
            hint=f"links: {listing(links)}",
        )
    steps = " -> ".join(f"{part.prefix} (to {part.to})" for part in cycle)
    return ManifestError(
        f"parts are attached to each other in a cycle: {steps}",
        file=f"{cycle[0].key}.to",
        hint="attach one of them to a link of the main source",
    )


def _join(root: etree._Element, part: Part, base_dir: Path, source: int) -> list[str]:
    """Append ``part`` (input number ``source``) to ``root``, prefixed, with a fixed joint to
    its ``to`` link."""
    warnings: list[str] = []
    tree = _parse(part.xml, part.label, warnings)
    _mark(tree, source)
    part_links = _names(tree, "link")
    children = {
        child.get("link") for joint in tree.findall("joint") for child in joint.findall("child")
    }
    roots = [name for name in part_links if name not in children]
    if len(roots) != 1:
        raise InputError(
            f"the part has {len(roots)} root links ({', '.join(roots) or 'none'}); it needs one",
            file=part.label,
            hint=f"fix the part of {part.key}",
        )
    _check_collisions(root, tree, part)
    dropped = sorted(
        {
            f"<{child.tag}>{' without a reference' if child.tag == 'gazebo' else ''}"
            for child in tree
            if isinstance(child.tag, str) and not _kept(child)
        }
    )
    if dropped:
        warnings.append(
            f"{part.label}: the part's {', '.join(dropped)} left out (only its links, "
            "joints, materials, transmissions, ros2_control, sensors and the <gazebo> elements "
            "of its links are attached)"
        )
    for element in list(tree):
        if not _kept(element):
            continue
        _prefix_element(element, part.prefix)
        _rebase_files(element, part, base_dir)
        root.append(element)
    joint = etree.SubElement(root, "joint", name=f"{part.prefix}attachment", type="fixed")
    etree.SubElement(joint, "parent", link=part.to)
    etree.SubElement(joint, "child", link=part.prefix + roots[0])
    etree.SubElement(
        joint, "origin", xyz=" ".join(map(repr, part.xyz)), rpy=" ".join(map(repr, part.rpy))
    )
    return warnings


def _check_collisions(root: etree._Element, tree: etree._Element, part: Part) -> None:
    for tag in ("link", "joint", "material"):
        existing = set(_names(root, tag))
        if tag == "joint":
            existing.add(f"{part.prefix}attachment")
        clashes = sorted({part.prefix + name for name in _names(tree, tag)} & existing)
        if clashes:
            raise ManifestError(
                f"prefix '{part.prefix}' makes {tag} name '{clashes[0]}' of {part.label} "
                "collide with a name of the model",
                file=f"{part.key}.prefix",
                hint="choose a prefix no name of the model starts with",
            )


def _prefix_element(element: etree._Element, prefix: str) -> None:
    """Prefix the names ``element`` defines and the links, joints and materials it refers to."""
    tag = element.tag
    if tag in ("link", "joint", "material", "sensor"):
        element.set("name", prefix + element.get("name", ""))
    if tag == "gazebo":
        element.set("reference", prefix + (element.get("reference") or "").strip())
    for sub in element.iter():
        if sub is element:
            continue
        if tag == "sensor" and sub.tag == "parent":
            for key in ("link", "joint"):
                if sub.get(key) is not None:
                    sub.set(key, prefix + sub.get(key, ""))
            continue
        if tag == "gazebo" and sub.tag == "sensor" and sub.get("name"):
            sub.set("name", prefix + sub.get("name", ""))
            continue
        if sub.tag in ("parent", "child") and tag == "joint":
            sub.set("link", prefix + sub.get("link", ""))
        elif sub.tag == "mimic" and sub.get("joint") is not None:
            sub.set("joint", prefix + sub.get("joint", ""))
        elif (sub.tag == "material" and sub.get("name")) or (
            sub.tag in ("joint", "sensor", "actuator")
            and tag in ("transmission", "ros2_control")
            and sub.get("name")
        ):
            sub.set("name", prefix + sub.get("name", ""))


def _rebase_files(element: etree._Element, part: Part, base_dir: Path) -> None:
    """Mesh and texture references of the part, as paths relative to the main source's folder."""
    for sub in element.iter("mesh", "texture"):
        uri = sub.get("filename")
        if not uri or uri.startswith("file://") or Path(uri).is_absolute():
            continue
        try:
            path = part.resolve(uri)
        except InputError as exc:
            raise InputError(
                exc.message, file=part.label, line=sub.sourceline, hint=exc.hint
            ) from None
        sub.set("filename", Path(os.path.relpath(path, base_dir)).as_posix())
