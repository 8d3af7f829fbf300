"""Step ``scene``: the scene file that includes the robot and sets the stage around it."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.mjcf.scene import default_scene, scene_with
from mjcfbuild.steps.outputs import write_output


def run(payload: dict) -> dict:
    """Write the scene: the user's scene file verbatim, or the default scene."""
    if payload.get("scene_file"):
        data = Path(payload["scene_file"]).read_bytes()
    elif payload.get("scene_block"):
        block = payload["scene_block"]
        data = scene_with(
            payload["model"], payload["robot_file"], block["xml"], block["origin"], _floor(payload)
        )
    else:
        data = default_scene(payload["model"], payload["robot_file"], _floor(payload)).encode()
    outputs: dict[str, str] = {}
    write_output(Path(payload["output"]), data, outputs)
    return {"outputs": outputs}


def _floor(payload: dict) -> float:
    """The floor height: as set, or 0 lowered under the lowest collision point at home."""
    if payload.get("floor") != "auto":
        return float(payload.get("floor") or 0.0)
    lowest = json.loads(Path(payload["floor_record"]).read_text()).get("lowest_point")
    return min(float(lowest["height"]), 0.0) if lowest else 0.0
