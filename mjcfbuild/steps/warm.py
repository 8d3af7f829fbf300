"""Step ``warm``: MuJoCo processes a model's mesh products in a second worker while the model is
assembled in the first, so that the check or the previews compile it there quickly (see
mjcfbuild.check.loading). Not a task: the build starts it beside ``assemble``, and it writes
nothing."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.check.loading import warm_meshes
from mjcfbuild.steps.payloads import WarmPayload


def run(payload: dict) -> dict:
    """Process every mesh file in the payload's folders into this worker's MuJoCo cache."""
    request = WarmPayload.from_dict(payload)
    files = [
        str(path)
        for folder in request.folders
        if Path(folder).is_dir()
        for path in sorted(Path(folder).iterdir())
    ]
    warm_meshes(files)
    return {"outputs": {}}
