"""The ``compose`` family: each URDF or xacro part of ``attach:`` expanded by a task of its own
(``expand:<prefix>``), so editing a gripper's xacro re-expands the gripper alone, and the
``compose`` task joining the expanded parts to the expanded main source; the plan reads its
result. Mesh tasks are per mesh file as always, so the arm's meshes stay up to date when the
gripper changes."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.families.expand import expand_file_task
from mjcfbuild.families.parts import part_packages, part_source
from mjcfbuild.graph.family import Family, file_task, ros_environment, ros_package_index
from mjcfbuild.outputs import COMPOSED_URDF, SOURCE_URDF, part_urdf
from mjcfbuild.steps.payloads import ComposePayload, PartEntry

if TYPE_CHECKING:
    from mjcfbuild.graph.graph import Graph


def _composition_tasks(graph: Graph) -> list[dict]:
    """An ``expand:`` task per URDF or xacro part, and the ``compose`` task; none without."""
    from mjcfbuild.sources.origins import origins_file

    ctx, prefix = graph.ctx, graph.prefix
    tasks: list[dict] = []
    parts = [(i, part) for i, part in enumerate(ctx.manifest.attach) if part.source.kind != "mjcf"]
    if not parts:
        return tasks
    entries: list[PartEntry] = []
    for index, part in parts:
        source = part_source(ctx, index, part)
        packages = part_packages(ctx, index, part)
        output = part_urdf(ctx, index)
        tasks.append(
            expand_file_task(
                ctx,
                f"{prefix}expand:{part.prefix}",
                source,
                part.source.kind,
                part.source.xacro_args,
                packages,
                output,
                output.with_suffix(".deps.json"),
                args_at=f"attach[{index}].source.args",
                written=part.source.urdf or "",
            )
        )
        entries.append(
            PartEntry(
                urdf=str(output),
                label=ctx.label(output if part.source.kind == "xacro" else source),
                key=f"{ctx.manifest_label} attach[{index}]",
                prefix=part.prefix,
                to=part.to,
                xyz=list(part.pos),
                rpy=list(part.rpy),
                base_dir=str(source.parent),
                packages={name: str(path) for name, path in packages.items()},
            )
        )
    payload = ComposePayload(
        main=str(ctx.state(SOURCE_URDF)),
        main_label=ctx.label(
            ctx.state(SOURCE_URDF) if ctx.source_kind == "xacro" else ctx.source_path
        ),
        base_dir=str(ctx.source_base_dir),
        parts=entries,
        environment=ros_environment(ctx),
        package_index=ros_package_index(ctx),
        output=str(ctx.state(COMPOSED_URDF)),
        origins=str(origins_file(ctx.state(COMPOSED_URDF))),
    )
    inputs = [ctx.state(SOURCE_URDF), *(Path(e.urdf) for e in entries)]
    tasks.append(
        file_task(
            ctx,
            FAMILY,
            f"{prefix}compose",
            f"attach {', '.join(part.prefix for _, part in parts)}",
            payload,
            in_worker=False,
            # The inputs' origins too: a xacro line that moved moves the composed origins.
            file_dep=[
                *(p for e in inputs for p in (e, origins_file(e))),
            ],
            targets=[ctx.state(COMPOSED_URDF), origins_file(ctx.state(COMPOSED_URDF))],
        )
    )
    return tasks


FAMILY = Family(
    name="compose",
    step="mjcfbuild.steps.compose:run",
    payload=ComposePayload,
    format=2,  # 2: the origins of the composed lines
    tools=("lxml",),
    tasks=_composition_tasks,
    stage="planning",
)
