"""What of an MJCF model a preview picture shows, as XML text to compare between builds.

The previews show the model at its home pose, on the scene's floor, from fixed viewpoints. Joint
dynamics (damping, armature, friction, stiffness, limits), actuators, sensors, contact filters,
equality constraints, simulation options, masses and keyframes other than the home pose change
how the model moves, never how it looks there: :func:`drawn_xml` leaves them out.
Standard library only: the build process uses this on every rebuild that reached assembly.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from mjcfbuild.markup import xml_text

# Elements with no effect on a picture of the model at its reference pose.
_UNSEEN_ELEMENTS = {"actuator", "sensor", "contact", "equality", "keyframe", "option", "custom"}
# Attributes, by element, with no effect on that picture.
_UNSEEN_ATTRIBUTES = {
    "joint": {
        "damping",
        "armature",
        "frictionloss",
        "stiffness",
        "springref",
        "springdamper",
        "limited",
        "range",
        "actuatorfrcrange",
        "actuatorfrclimited",
        "actuatorgravcomp",
        "solreflimit",
        "solimplimit",
        "solreffriction",
        "solimpfriction",
        "margin",
    },
    "inertial": {"mass", "diaginertia", "fullinertia"},
}


def drawn_xml(root: ET.Element) -> bytes:
    """The model under ``root`` as its pictures show it: without what cannot show, with the
    home pose. ``root`` is changed in place."""
    home = [key.get("qpos", "") for key in root.iter("key") if key.get("name") == "home"]
    _strip(root)
    return _serialised(root) + f"\0home\0{home}".encode()


# How ElementTree escapes attribute values beyond &, < and >.
_ATTRIBUTE_ESCAPES = {'"': "&quot;", "\r": "&#13;", "\n": "&#10;", "\t": "&#09;"}


def _serialised(root: ET.Element) -> bytes:
    """The bytes ``ET.tostring(root)`` gives, written without recursion (ElementTree's writer
    recurses once per nested element, and bodies nest as deep as a chain is long)."""
    elements = list(root.iter())
    if any(
        not isinstance(e.tag, str) or "{" in e.tag or "{" in "".join(e.attrib) for e in elements
    ):
        return ET.tostring(root)  # comments or namespaces: never in MuJoCo's MJCF, and shallow
    parts: list[str] = []
    pending: list[ET.Element | str] = [root]
    while pending:
        element = pending.pop()
        if isinstance(element, str):
            parts.append(element)
            continue
        parts.append("<" + element.tag)
        parts.extend(f' {k}="{xml_text(v, _ATTRIBUTE_ESCAPES)}"' for k, v in element.items())
        tail = xml_text(element.tail) if element.tail else ""
        if element.text or len(element):
            parts.append(">" + (xml_text(element.text) if element.text else ""))
            pending.append(f"</{element.tag}>{tail}")
            pending.extend(reversed(list(element)))
        else:
            parts.append(" />" + tail)
    return "".join(parts).encode("us-ascii", "xmlcharrefreplace")


def drawn_model_xml(path: Path) -> bytes | None:
    """:func:`drawn_xml` of the MJCF file at ``path`` with the files it includes in place
    (``<include file>`` names them relative to the main file's folder, as MuJoCo reads them);
    None if one of them cannot be read."""
    try:
        root = ET.parse(path).getroot()
        _include(root, path.parent)
    except (OSError, ET.ParseError, _IncludesTooDeep):
        return None
    return drawn_xml(root)


class _IncludesTooDeep(Exception):
    """Files that include each other more than 20 deep (or in a loop)."""


def _include(root: ET.Element, folder: Path) -> None:
    """Put the files ``<include>`` names in place, walking without recursion (bodies nest as
    deep as a chain is long)."""
    pending = [(root, 0)]
    splices = []  # (element, its <include>, the included file's root), outer ones first
    while pending:
        element, depth = pending.pop()
        for child in list(element):
            if child.tag != "include":
                pending.append((child, depth))
                continue
            if depth >= 20:
                raise _IncludesTooDeep
            included = ET.parse(folder / child.get("file", "")).getroot()
            splices.append((element, child, included))
            pending.append((included, depth + 1))
    for element, child, included in reversed(splices):  # inner files are complete first
        position = list(element).index(child)
        element[position : position + 1] = list(included)


def _strip(root: ET.Element) -> None:
    pending = [root]
    while pending:
        element = pending.pop()
        for child in list(element):
            if child.tag in _UNSEEN_ELEMENTS:
                element.remove(child)
            else:
                pending.append(child)
        for name in _UNSEEN_ATTRIBUTES.get(element.tag, ()):
            element.attrib.pop(name, None)
