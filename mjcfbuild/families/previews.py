"""The ``previews`` family: pictures of the robot at home on its floor (``check.previews``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mjcfbuild.graph.family import Family, file_task
from mjcfbuild.graph.render_inputs import RenderInputsUnchanged
from mjcfbuild.outputs import ASSEMBLY_REPORT, PREVIEWS_RECORD, report_dir
from mjcfbuild.steps.payloads import PreviewsPayload
from mjcfbuild.steps.versions import PREVIEWS

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


ORDER = (
    "three_quarter_visual",
    "side_visual",
    "top_visual",
    "closeup_visual",
    "three_quarter_collision",
    "side_collision",
    "closeup_collision",
)


def _tasks(graph: Graph) -> list[dict]:
    ctx = graph.ctx
    if not (graph.checks and ctx.manifest.check.previews):
        return []
    # The scene: the robot at home, on its floor.
    payload = PreviewsPayload(
        folder=str(report_dir(ctx) / "previews"),
        model=str(ctx.scene_path),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        record=str(ctx.state(PREVIEWS_RECORD)),
        cache=ctx.cache_settings(),
    )
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}previews",
        "previews",
        payload,
        in_worker=True,
        # Not the model file: only what a picture shows (a damping change leaves them alone),
        # and the scene, whose floor the pictures show.
        file_dep=[ctx.scene_path],
        targets=[ctx.state(PREVIEWS_RECORD)],
        extra_uptodate=[RenderInputsUnchanged(ctx.robot_path, ctx.assets_dir, ctx.session.hashes)],
        after=[f"{graph.prefix}assemble"],
    )
    return [task]


def _report(ctx: GraphContext) -> dict:
    """The pictures in the report folder, in the order the report shows them."""
    pictures = sorted(
        (p.name for p in (report_dir(ctx) / "previews").glob("*.png")),
        key=lambda n: ORDER.index(n[:-4]) if n[:-4] in ORDER else 99,
    )
    return {"previews": [f"previews/{name}" for name in pictures]}


FAMILY = Family(
    name="previews",
    step="mjcfbuild.steps.previews:run",
    payload=PreviewsPayload,
    format=PREVIEWS.format,  # declared beside the step, which keys its products by it
    tools=PREVIEWS.tools,
    tasks=_tasks,
    compiles_model=True,
    report_only=True,
    report=_report,
)
