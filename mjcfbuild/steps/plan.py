"""Step ``plan``: parse the URDF, resolve every file it names, and list the meshes to convert."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.errors import InputError
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.urdf.parse import parse_urdf
from mjcfbuild.urdf.resolve import resolve_files


def run(payload: dict) -> dict:
    """Write the build plan (robot model and mesh list) to ``payload['output']``."""
    packages = PackageResolver(
        {name: Path(folder) for name, folder in payload["packages"].items()},
        payload["environment"],
    )
    try:
        robot = parse_urdf(Path(payload["urdf"]).read_bytes(), payload["display"])
        resolve_files(robot, Path(payload["base_dir"]), packages)
    except InputError as exc:
        if payload.get("expanded_from") and exc.hint is None:
            exc.hint = f"the line is in the expansion of {payload['expanded_from']}"
        raise
    meshes = {
        shape.geometry.mesh_id: shape.geometry.path
        for link in robot.links
        for shape in link.shapes
        if shape.geometry.kind == "mesh"
    }
    plan = {
        "robot": robot.to_dict(),
        "meshes": [{"id": mesh_id, "path": path} for mesh_id, path in sorted(meshes.items())],
    }
    outputs: dict[str, str] = {}
    text = json.dumps(plan, indent=1, sort_keys=True) + "\n"
    write_output(Path(payload["output"]), text.encode(), outputs)
    return {"outputs": outputs, "warnings": robot.warnings}
