"""Step ``warm``: a second worker is prepared for the steps that will compile the model while
the first is busy: it imports their modules and has MuJoCo process the model's mesh products
(see mjcfbuild.check.loading). Not a task: the build starts it beside the self-collision
matrix (for the assembly) and beside the assembly (for the check and the previews), and it
writes nothing."""

from __future__ import annotations

import contextlib
import importlib
from pathlib import Path

from mjcfbuild.check.loading import warm_meshes
from mjcfbuild.steps.payloads import WarmPayload


def run(payload: dict) -> dict:
    """Import the payload's modules, then process every mesh file in its folders into this
    worker's MuJoCo cache."""
    request = WarmPayload.from_dict(payload)
    for module in request.modules:
        with contextlib.suppress(Exception):  # the step that imports it reports the error
            importlib.import_module(module)
    files = [
        str(path)
        for folder in request.folders
        if Path(folder).is_dir()
        for path in sorted(Path(folder).iterdir())
    ]
    warm_meshes(files)
    return {"outputs": {}}
