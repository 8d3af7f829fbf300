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
    return ET.tostring(root) + f"\0home\0{home}".encode()


def drawn_model_xml(path: Path) -> bytes | None:
    """:func:`drawn_xml` of the MJCF file at ``path`` with the files it includes in place
    (``<include file>`` names them relative to the main file's folder, as MuJoCo reads them);
    None if one of them cannot be read."""
    try:
        root = ET.parse(path).getroot()
        _include(root, path.parent, depth=0)
    except (OSError, ET.ParseError, RecursionError):
        return None
    return drawn_xml(root)


def _include(element: ET.Element, folder: Path, depth: int) -> None:
    if depth > 20:
        raise RecursionError("includes nested too deep")
    for child in list(element):
        if child.tag != "include":
            _include(child, folder, depth)
            continue
        included = ET.parse(folder / child.get("file", "")).getroot()
        _include(included, folder, depth + 1)
        position = list(element).index(child)
        element[position : position + 1] = list(included)


def _strip(element: ET.Element) -> None:
    for child in list(element):
        if child.tag in _UNSEEN_ELEMENTS:
            element.remove(child)
        else:
            _strip(child)
    for name in _UNSEEN_ATTRIBUTES.get(element.tag, ()):
        element.attrib.pop(name, None)
