"""Step ``training``: the training variant beside the model, and its scene."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.actuators import for_mujoco3
from mjcfbuild.errors import InputError
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import TrainingPayload
from mjcfbuild.steps.scene import scene_bytes


def run(payload: dict) -> dict:
    """Write the variant, its scene and a record of what was changed."""
    from mjcfbuild.training.variant import VariantSettings, build_variant

    request = TrainingPayload.from_dict(payload)
    settings = dict(request.settings)
    for key in ("floor_add", "floor_remove"):
        settings[key] = tuple(settings[key])
    verdicts = []
    if request.self_collision:
        verdicts = json.loads(Path(request.self_collision).read_text())["pairs"]
    variant = build_variant(request.model, verdicts, VariantSettings(**settings))
    outputs: dict[str, str] = {}
    # MJX runs with the MuJoCo it was released with (3.x), which refuses one attribute 4.0 writes.
    xml = for_mujoco3(f"<!-- {request.header} -->\n{variant.xml}".encode())
    write_output(Path(request.output), xml, outputs)
    scene = scene_bytes(request.scene)
    if request.scene.scene_file:
        scene = _include_variant(scene, request.robot_file, request.scene.robot_file, request)
    write_output(Path(request.scene.output), scene, outputs)
    # The files it wrote, by name in the output folder: a build without output.training, or
    # with other names, removes them (engine.training_files).
    files = [Path(request.output).name, Path(request.scene.output).name]
    record = json.dumps({**variant.to_dict(), "files": files}, indent=1, sort_keys=True).encode()
    write_output(Path(request.record), record, outputs)
    return {"outputs": outputs, "note": "; ".join(variant.notes)}


def _include_variant(scene: bytes, full: str, variant: str, request: TrainingPayload) -> bytes:
    """A user's scene file with its include of the full model turned to the variant."""
    included = f'file="{full}"'.encode()
    if included not in scene:
        raise InputError(
            f"the scene file does not include {full} (<include {included.decode()}/>), so the "
            "training variant's scene cannot include the variant in its place",
            file=request.scene.scene_file,
        )
    return scene.replace(included, f'file="{variant}"'.encode())
