"""The ``scene`` family: the scene around the model (a floor, light, the user's scene file or
block), beside it."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.graph.family import Family, file_task, require_file
from mjcfbuild.outputs import FLOOR_RECORD
from mjcfbuild.steps.payloads import ScenePayload

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph
    from mjcfbuild.steps.plan_record import Plan


def scene_payload(ctx: GraphContext, plan: Plan, robot_file: str, output: Path) -> ScenePayload:
    """The scene around ``robot_file`` (the model, or the training variant)."""
    scene = ctx.manifest.scene
    source = ctx.resolve(scene.file) if scene.file else None
    if source is not None:
        require_file(ctx, source, "scene file", "scene.file")
    block = None
    if scene.mjcf:
        # The manifest relative to its own folder: the same parameter whichever folder the
        # build runs in (errors are shown relative to the current folder when reported).
        block = {"xml": scene.mjcf, "origin": f"{ctx.manifest_output_label} scene.mjcf"}
    elif source is None:
        for where in ("file", "urdf"):
            found = (plan.inputs.get(where) or {}).get("scene")
            if found:
                block = found
                break
    return ScenePayload(
        scene_file=str(source) if source else None,
        scene_block=block,
        model=ctx.manifest.name,
        robot_file=robot_file,
        floor=ctx.manifest.placement.floor,
        floor_record=str(ctx.state(FLOOR_RECORD)),
        output=str(output),
    )


def _tasks(graph: Graph) -> list[dict]:
    ctx, prefix = graph.ctx, graph.prefix
    payload = scene_payload(ctx, graph.plan, ctx.manifest.robot_file, ctx.scene_path)
    source = Path(payload.scene_file) if payload.scene_file else None
    auto_floor = ctx.manifest.placement.floor == "auto"
    task = file_task(
        ctx,
        FAMILY,
        f"{prefix}scene",
        f"scene {ctx.manifest.output.scene}",
        payload,
        in_worker=False,
        file_dep=([source] if source else []) + ([ctx.state(FLOOR_RECORD)] if auto_floor else []),
        targets=[ctx.scene_path],
        # Outputs change together: a build whose model fails leaves the scene alone too.
        after=[f"{prefix}assemble"],
    )
    return [task]


FAMILY = Family(
    name="scene",
    step="mjcfbuild.steps.scene:run",
    payload=ScenePayload,
    format=3,
    tools=("lxml",),
    tasks=_tasks,
)
