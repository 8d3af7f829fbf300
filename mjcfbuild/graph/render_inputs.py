"""What the preview pictures are drawn from, so a change that cannot show does not redraw them.

The digest of the model as drawn (:func:`mjcfbuild.check.drawn.drawn_xml`: without joint
dynamics, actuators, masses and the like, with the home pose), together with the bytes of every
file in its assets folder, is the previews task's input, beside the scene file: a damping change
reruns the check (the simulation sees it) and leaves the pictures alone. Which pictures a change
redraws is for the previews step to decide (mjcfbuild.check.previews).
"""

from __future__ import annotations

import hashlib
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from mjcfbuild.check.drawn import drawn_xml
from mjcfbuild.graph.hashes import HashCache


def render_digest(model: Path, assets: Path, hashes: HashCache) -> str | None:
    """The digest of what the previews of ``model`` show; None if the model cannot be read."""
    try:
        root = ET.parse(model).getroot()
    except (OSError, ET.ParseError):
        return None
    digest = hashlib.sha256(drawn_xml(root))
    if assets.is_dir():
        for path in sorted(p for p in assets.rglob("*") if p.is_file()):
            digest.update(f"\0{path.relative_to(assets)}\0{hashes.md5(path)}".encode())
    return digest.hexdigest()


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
