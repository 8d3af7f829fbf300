"""The ``srdf`` family: the SRDF robot.yaml names (or, for a floating robot, the one shipped
beside its description) read for its collision pairs and its home pose."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.graph.family import (
    Family,
    discovered_inputs,
    file_task,
    package_folders,
    require_file,
    ros_environment,
    ros_package_index,
)
from mjcfbuild.outputs import SRDF_DEPS, SRDF_SUMMARY
from mjcfbuild.steps.payloads import SrdfPayload

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


def srdf_home_state(ctx: GraphContext) -> str | None:
    """The SRDF group state that is the home pose, when an SRDF is read."""
    settings = ctx.manifest.self_collision
    return settings.home_state if settings != "none" and settings.srdf else None


def _given_home_state(ctx: GraphContext) -> str | None:
    """self_collision.home_state where robot.yaml writes it (not its default)."""
    settings = ctx.manifest.self_collision
    if settings == "none" or "home_state" not in settings.model_fields_set:
        return None
    return settings.home_state


def _named_srdf(ctx: GraphContext) -> Path | None:
    """The SRDF robot.yaml names (self_collision.srdf)."""
    settings = ctx.manifest.self_collision
    if settings == "none" or settings.srdf is None:
        return None
    return ctx.resolve(settings.srdf)


def srdf_source(graph: Graph) -> Path | None:
    """The SRDF the build reads: the one robot.yaml names, else, for a floating robot (by
    robot.yaml's free_joint or the URDF's own floating joint), the one shipped beside the
    description (for its standing pose; see selfcollision.discover)."""
    from mjcfbuild.mjcf.bodies import floating_base

    ctx = graph.ctx
    named = _named_srdf(ctx)
    if named is not None:
        return named
    if ctx.source_kind == "description":
        return None
    if not floating_base(graph.robot, ctx.manifest.options.free_joint):
        return None
    from mjcfbuild.selfcollision.discover import find_srdf

    return find_srdf(ctx.source_path)


def srdf_searches(ctx: GraphContext) -> dict[str, list[str]]:
    """Where the build looks for an SRDF shipped beside the description (file-name patterns
    and what each matches now), where it may look: robot.yaml names none and the source is a
    file. An SRDF that appears there later gives a floating robot its standing pose, so the
    no-op stamp records these (a fixed robot's rerun then finds nothing to do)."""
    if _named_srdf(ctx) is not None or ctx.source_kind == "description":
        return {}
    from mjcfbuild.selfcollision.discover import srdf_searches as searches

    return searches(ctx.source_path)


def srdf_summary(graph: Graph) -> Path | None:
    """What the ``srdf`` task writes, when the build reads an SRDF."""
    return graph.ctx.state(SRDF_SUMMARY) if srdf_source(graph) else None


def _tasks(graph: Graph) -> list[dict]:
    ctx = graph.ctx
    source = srdf_source(graph)
    if source is None:
        return []
    named = _named_srdf(ctx) is not None
    if named:
        require_file(ctx, source, "SRDF", "self_collision.srdf")
    # The files an SRDF xacro included, as its last run recorded them (the expand family's
    # depfile): declared, so an edit of one reruns the task.
    read, stale = discovered_inputs(ctx, ctx.state(SRDF_DEPS))
    payload = SrdfPayload(
        source=str(source),
        label=ctx.label(source),
        args=ctx.manifest.source.xacro_args if named else {},
        packages=package_folders(ctx.resolver.explicit),
        environment=ros_environment(ctx),
        package_index=ros_package_index(ctx),
        output=str(ctx.state(SRDF_SUMMARY)),
        depfile=str(ctx.state(SRDF_DEPS)),
        discovered=not named,
        home_state=_given_home_state(ctx) if named else None,
        manifest_label=ctx.manifest_output_label,
    )
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}srdf",
        f"srdf {ctx.label(source)}",
        payload,
        in_worker=source.name.endswith(".xacro"),
        file_dep=[source, *read],
        targets=[ctx.state(SRDF_SUMMARY), ctx.state(SRDF_DEPS)],
        extra_uptodate=stale,
    )
    return [task]


FAMILY = Family(
    name="srdf",
    step="mjcfbuild.steps.srdf:run",
    payload=SrdfPayload,
    format=3,  # 3: each group_state joint's line, for errors naming it
    tools=("xacro", "lxml"),
    tasks=_tasks,
)
