"""The ``tuning`` family: each actuator group's step and sine response (``check.tuning``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mjcfbuild.graph.family import Family, file_task, read_record
from mjcfbuild.outputs import ASSEMBLY_REPORT, TUNING_RECORD, report_dir
from mjcfbuild.steps.payloads import TuningPayload

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


def _tasks(graph: Graph) -> list[dict]:
    """Reruns when the model or its actuators change, and alone: neither the check nor the
    previews wait for it."""
    ctx = graph.ctx
    if not (graph.checks and ctx.manifest.check.tuning):
        return []
    payload = TuningPayload(
        folder=str(report_dir(ctx) / "tuning"),
        rules=[rule.model_dump(mode="json") for rule in ctx.manifest.actuators.rules],
        model=str(ctx.robot_path),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        record=str(ctx.state(TUNING_RECORD)),
    )
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}tuning",
        "tuning report",
        payload,
        in_worker=True,
        file_dep=[ctx.robot_path, ctx.state(ASSEMBLY_REPORT)],
        targets=[ctx.state(TUNING_RECORD)],
        after=[f"{graph.prefix}assemble"],
    )
    return [task]


def _report(ctx: GraphContext) -> dict:
    return {"tuning": read_record(ctx.state(TUNING_RECORD)) if ctx.manifest.check.tuning else {}}


FAMILY = Family(
    name="tuning",
    step="mjcfbuild.steps.tuning:run",
    payload=TuningPayload,
    format=1,
    tools=("mujoco", "numpy", "pillow"),
    tasks=_tasks,
    compiles_model=True,
    report_only=True,
    report=_report,
)
