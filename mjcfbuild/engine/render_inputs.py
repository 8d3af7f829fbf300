"""What the preview pictures are drawn from, so a change that cannot show does not redraw them.

The previews show the model at its home pose, on the scene's floor, from fixed viewpoints. Joint
dynamics (damping, armature, friction, stiffness, limits), actuators, sensors, contact filters,
equality constraints, simulation options, masses and keyframes other than the home pose change
how the model moves, never how it looks there. The digest of the model without them (with the
home pose), together with the bytes of every file in its assets folder, is the previews task's
input, beside the scene file: a damping change reruns the check (the simulation sees it) and
leaves the pictures alone.
"""

from __future__ import annotations

import hashlib
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from mjcfbuild.engine.hashes import HashCache

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


def render_digest(model: Path, assets: Path, hashes: HashCache) -> str | None:
    """The digest of what the previews of ``model`` show; None if the model cannot be read."""
    try:
        root = ET.parse(model).getroot()
    except (OSError, ET.ParseError):
        return None
    # The pictures show the robot at home: its keyframe's pose counts, nothing else of it.
    home = [k.get("qpos", "") for k in root.iter("key") if k.get("name") == "home"]
    _strip(root)
    digest = hashlib.sha256(ET.tostring(root))
    digest.update(f"\0home\0{home}".encode())
    if assets.is_dir():
        for path in sorted(p for p in assets.rglob("*") if p.is_file()):
            digest.update(f"\0{path.relative_to(assets)}\0{hashes.md5(path)}".encode())
    return digest.hexdigest()


def _strip(element: ET.Element) -> None:
    for child in list(element):
        if child.tag in _UNSEEN_ELEMENTS:
            element.remove(child)
        else:
            _strip(child)
    for name in _UNSEEN_ATTRIBUTES.get(element.tag, ()):
        element.attrib.pop(name, None)


class RenderInputsUnchanged:
    """A doit up-to-date check: the previews' digest equals the one of their last run."""

    KEY = "_render_inputs"

    def __init__(self, model: Path, assets: Path, hashes: HashCache) -> None:
        self.model = model
        self.assets = assets
        self.hashes = hashes
        self.reason = ""

    def configure_task(self, task: Any) -> None:
        """Save the digest with the task's values when it succeeds (doit hook)."""
        task.value_savers.append(lambda: {self.KEY: self.digest()})

    def digest(self) -> str | None:
        """The current digest of the model as drawn."""
        return render_digest(self.model, self.assets, self.hashes)

    def __call__(self, task: Any, values: dict) -> bool:
        current = self.digest()
        if current is not None and values.get(self.KEY) == current:
            return True
        self.reason = "the model as drawn changed (geometry, poses, materials or meshes)"
        return False

    def __repr__(self) -> str:
        return "the model as drawn"
