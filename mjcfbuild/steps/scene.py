"""Step ``scene``: the scene file that includes the robot and sets the stage around it."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.mjcf.scene import default_scene, scene_with
from mjcfbuild.steps.outputs import write_output


def run(payload: dict) -> dict:
    """Write the scene: the user's scene file verbatim, or the default scene."""
    if payload.get("scene_file"):
        data = Path(payload["scene_file"]).read_bytes()
    elif payload.get("scene_block"):
        block = payload["scene_block"]
        data = scene_with(payload["model"], payload["robot_file"], block["xml"], block["origin"])
    else:
        data = default_scene(payload["model"], payload["robot_file"]).encode()
    outputs: dict[str, str] = {}
    write_output(Path(payload["output"]), data, outputs)
    return {"outputs": outputs}
