"""The ``page`` family: the interactive report page (``output.page``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mjcfbuild.graph.family import Family, file_task
from mjcfbuild.outputs import ASSEMBLY_REPORT, PAGE_FILES, report_dir
from mjcfbuild.steps.payloads import PagePayload

if TYPE_CHECKING:
    from mjcfbuild.graph.graph import Graph


def _tasks(graph: Graph) -> list[dict]:
    """The model's files and MuJoCo's WebAssembly build bundled beside the report. The
    report's tables are not its input: the build writes them with the report
    (engine/report.py), failed checks included, which a failed check task would stop a task
    after it from doing."""
    ctx, prefix = graph.ctx, graph.prefix
    if not ctx.manifest.output.page:
        return []
    from mjcfbuild.page import web_files
    from mjcfbuild.page.vendor import INTEGRITY, VERSION

    folder = report_dir(ctx)
    payload = PagePayload(
        name=ctx.manifest.name,
        mujoco_js=f"{VERSION} {INTEGRITY}",
        model=str(ctx.robot_path),
        scene=str(ctx.scene_path),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        assets=str(ctx.assets_dir),
        hold_tolerance=ctx.manifest.check.hold_tolerance,
        folder=str(folder),
    )
    task = file_task(
        ctx,
        FAMILY,
        f"{prefix}page",
        "report page report/index.html",
        payload,
        in_worker=False,  # no MuJoCo, no native code: files read, encoded and written
        file_dep=[
            ctx.robot_path,
            ctx.scene_path,
            ctx.state(ASSEMBLY_REPORT),
            *web_files(),  # the page's template, script and style
        ],
        targets=[folder / name for name in PAGE_FILES],
        after=[f"{prefix}assemble", f"{prefix}scene"],
    )
    return [task]


FAMILY = Family(
    name="page",
    step="mjcfbuild.steps.page:run",
    payload=PagePayload,
    format=3,  # 2: bold, pictures and quotes in the tables; the diff's changes section; 3: no
    # "(null)" after a deviation no joint made
    tools=(),
    tasks=_tasks,
)
