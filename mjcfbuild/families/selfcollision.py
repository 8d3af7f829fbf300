"""The ``selfcollision`` family: the collision matrix, MoveIt's reasons for each pair."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.families.decompose import decomposition_files
from mjcfbuild.families.srdf import srdf_summary
from mjcfbuild.graph.family import Family, file_task
from mjcfbuild.outputs import SELF_COLLISION, product_summary
from mjcfbuild.steps.payloads import SelfCollisionPayload
from mjcfbuild.steps.versions import SELFCOLLISION

if TYPE_CHECKING:
    from mjcfbuild.graph.graph import Graph


def self_collision_matrix(graph: Graph) -> Path | None:
    """What the ``selfcollision`` task writes, when self-collision is on."""
    return graph.ctx.state(SELF_COLLISION) if graph.ctx.manifest.self_collision != "none" else None


def _tasks(graph: Graph) -> list[dict]:
    # Here, not above: the step imports this module for its versions, without the manifest.
    from mjcfbuild.families.parts import urdf_home
    from mjcfbuild.selfcollision.parts import collision_digest
    from mjcfbuild.selfcollision.robot import collision_robot

    ctx, robot, choices, parts = graph.ctx, graph.robot, graph.choices, graph.parts
    settings = ctx.manifest.self_collision
    if settings == "none":
        return []
    meshes = sorted(m for m, r in graph.roles.items() if set(r) - {"visual"})
    decompositions = decomposition_files(ctx, graph.decomposed)
    srdf = srdf_summary(graph)
    initial = {
        joint["name"]: joint["initial"]
        for joint in graph.plan.ros2_control.get("joints", [])
        if joint.get("initial") is not None
    }
    payload = SelfCollisionPayload(
        robot=collision_robot(robot, choices).to_dict(),
        choices=[choice.to_dict() for choice in choices],
        fuse_static=ctx.manifest.options.fuse_static,
        free_joint=ctx.manifest.options.free_joint,
        decompositions=decompositions,
        initial=initial,
        home=urdf_home(robot, ctx.manifest.home),  # MJCF parts' joints are not in the matrix
        keep=[list(pair) for pair in settings.keep],
        home_state=settings.home_state,
        settings={
            "samples": settings.samples,
            "seed": settings.seed,
            "exclude_never": settings.exclude_never,
        },
        srdf=str(srdf) if srdf else None,
        products={m: str(product_summary(ctx, m)) for m in meshes},
        product_dirs={m: str(ctx.products_dir / m) for m in meshes},
        manifest_label=ctx.manifest_output_label,
        cache=ctx.cache_settings(),
        output=str(ctx.state(SELF_COLLISION)),
        mjcf_parts=list(parts),
        part_digests=[collision_digest(Path(part.xml), Path(part.summary)) for part in parts],
    )
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}selfcollision",
        "self-collision matrix",
        payload,
        in_worker=True,
        file_dep=[
            *(product_summary(ctx, m) for m in meshes),
            *(Path(d.summary) for d in decompositions),
            *([srdf] if srdf else []),
        ],
        targets=[ctx.state(SELF_COLLISION)],
    )
    return [task]


FAMILY = Family(
    name="selfcollision",
    step="mjcfbuild.steps.selfcollision:run",
    payload=SelfCollisionPayload,
    format=SELFCOLLISION.format,  # declared beside the step, which keys its products by it
    tools=SELFCOLLISION.tools,
    tasks=_tasks,
    compiles_model=True,
)
