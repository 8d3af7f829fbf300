"""What of an ``attach:`` MJCF part decides its contacts, as one digest.

The self-collision matrix covers the parts' geoms, so it must rerun when a part's bodies,
joints or geoms change, but not when its actuators, sensors, joint dynamics or keyframes do
(the normalised part file changes for those too). The digest is of the normalised part with
those left out, and of the part's bodies and home pose.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from lxml import etree

# Elements and attributes that never change which geoms touch where.
_IGNORED_ELEMENTS = ("actuator", "sensor", "keyframe", "custom", "extension", "visual", "statistic")
_IGNORED_ATTRIBUTES = (
    "damping",
    "armature",
    "frictionloss",
    "stiffness",
    "springref",
    "actuatorfrcrange",
    "actuatorgravcomp",
    "rgba",
    "material",
)


def collision_digest(xml: Path, summary: Path) -> str:
    """A digest of the part's contact-relevant content (an unreadable file gives a digest
    that differs from every readable one, and the step reports the file)."""
    digest = hashlib.md5(usedforsecurity=False)
    try:
        parser = etree.XMLParser(remove_comments=True, huge_tree=True)  # bodies nest deep
        root = etree.parse(str(xml), parser).getroot()
        data = json.loads(summary.read_text())
    except (OSError, ValueError, etree.XMLSyntaxError) as exc:
        return f"unreadable: {exc}"
    for element in list(root.iter()):
        if not isinstance(element.tag, str):
            continue
        if element.tag in _IGNORED_ELEMENTS and element.getparent() is not None:
            element.getparent().remove(element)
            continue
        for name in _IGNORED_ATTRIBUTES:
            element.attrib.pop(name, None)
    digest.update(etree.tostring(root, method="c14n"))
    relevant = {"bodies": data.get("bodies"), "home_qpos": data.get("home_qpos")}
    digest.update(json.dumps(relevant, sort_keys=True).encode())
    return digest.hexdigest()
