"""Step ``scene``: the scene file that includes the robot and sets the stage around it."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.mjcf.scene import default_scene, scene_with
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import ScenePayload


def run(payload: dict) -> dict:
    """Write the scene: the user's scene file verbatim, or the default scene."""
    request = ScenePayload.from_dict(payload)
    outputs: dict[str, str] = {}
    write_output(Path(request.output), scene_bytes(request), outputs)
    return {"outputs": outputs}


def scene_bytes(request: ScenePayload) -> bytes:
    """The scene's content: the user's scene file verbatim, a scene block, or the default."""
    if request.scene_file:
        data = Path(request.scene_file).read_bytes()
    elif request.scene_block:
        block = request.scene_block
        data = scene_with(
            request.model, request.robot_file, block["xml"], block["origin"], _floor(request)
        )
    else:
        data = default_scene(request.model, request.robot_file, _floor(request)).encode()
    return data


def _floor(request: ScenePayload) -> float:
    """The floor height: as set, or 0 lowered under the lowest collision point at home."""
    if request.floor != "auto":
        return float(request.floor or 0.0)
    lowest = json.loads(Path(request.floor_record).read_text()).get("lowest_point")
    return min(float(lowest["height"]), 0.0) if lowest else 0.0
