"""The ``decompose`` family: one task per collision mesh that needs convex parts (its hull
where close enough, else CoACD's decomposition)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.graph.family import Family, file_task, largest_first, read_record
from mjcfbuild.outputs import decomposition_dir, product_summary
from mjcfbuild.steps.payloads import DecomposePayload, DecompositionFiles
from mjcfbuild.steps.versions import DECOMPOSE

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


def _tasks(graph: Graph) -> list[dict]:
    decomposed, paths = graph.decomposed, graph.paths
    return [
        _decompose_task(graph.ctx, name, *decomposed[name], graph.prefix)
        for name in largest_first(decomposed, lambda name: paths[decomposed[name][0]])
    ]


def _decompose_task(ctx: GraphContext, name: str, mesh_id: str, params: dict, prefix: str) -> dict:
    folder = decomposition_dir(ctx, name)
    payload = DecomposePayload(
        params=params,
        product_summary=str(product_summary(ctx, mesh_id)),
        product_dir=str(ctx.products_dir / mesh_id),
        output_dir=str(folder),
        summary=str(folder.with_suffix(".json")),
        cache=ctx.cache_settings(),
    )
    return file_task(
        ctx,
        FAMILY,
        f"{prefix}decompose:{name}",
        f"decompose {name}",
        payload,
        in_worker=True,
        file_dep=[product_summary(ctx, mesh_id)],
        targets=[folder.with_suffix(".json")],
    )


def decomposition_files(
    ctx: GraphContext, decomposed: dict[str, tuple[str, dict]]
) -> list[DecompositionFiles]:
    """The decompositions as the tasks that read them are given them (their summaries are
    those tasks' file dependencies)."""
    return [
        DecompositionFiles(
            mesh_id=mesh_id,
            params=params,
            folder=str(decomposition_dir(ctx, name)),
            summary=str(decomposition_dir(ctx, name).with_suffix(".json")),
        )
        for name, (mesh_id, params) in decomposed.items()
    ]


def decomposition_summaries(ctx: GraphContext) -> list[tuple[Path, dict]]:
    """Each decomposition's record, by name."""
    found = []
    for path in sorted(decomposition_dir(ctx, "any").parent.glob("*.json")):
        summary = read_record(path)
        if "parts" in summary:
            found.append((path, summary))
    return found


def _report(ctx: GraphContext) -> dict:
    """Per decomposition of this build: hull kept or CoACD, parts, concavities (its seconds
    are in build-stats.json)."""
    rows = [
        {
            "name": path.stem,
            "method": summary.get("method", "coacd"),
            "parts": len(summary["parts"]),
            "hull_concavity": summary.get("hull_concavity"),
            "concavity": summary.get("concavity"),
        }
        for path, summary in decomposition_summaries(ctx)
    ]
    return {"decompositions": rows, "products": {"decompositions": len(rows)}}


FAMILY = Family(
    name="decompose",
    step="mjcfbuild.steps.decompose:run",
    payload=DecomposePayload,
    format=DECOMPOSE.format,  # declared beside the step, which keys its products by it
    tools=DECOMPOSE.tools,
    tasks=_tasks,
    report=_report,
)
