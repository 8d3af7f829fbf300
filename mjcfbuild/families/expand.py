"""The ``expand`` family: xacro expanded, or a URDF read, into the URDF text the plan reads."""

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
from mjcfbuild.outputs import SOURCE_DEPS, SOURCE_URDF
from mjcfbuild.steps.payloads import ExpandPayload

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


def _tasks(graph: Graph) -> list[dict]:
    ctx = graph.ctx
    source = ctx.source_path
    require_file(ctx, source, "source file", f"source.{ctx.source_kind}")
    return [
        expand_file_task(
            ctx,
            f"{graph.prefix}expand",
            source,
            ctx.source_kind,
            ctx.manifest.source.xacro_args,
            ctx.resolver.explicit,
            ctx.state(SOURCE_URDF),
            ctx.state(SOURCE_DEPS),
            args_at="source.args",
            written=ctx.manifest.source.urdf or "",
        )
    ]


def _args_key(ctx: GraphContext, key: str) -> str:
    """Where xacro arguments were given, for the error about one no file declares."""
    from mjcfbuild.sources.expand import COMMAND_LINE

    if ctx.manifest_file is None and ctx.manifest_label == COMMAND_LINE:
        return COMMAND_LINE  # convert's NAME:=VALUE
    return f"{ctx.manifest_label} {key}"


def _empty_args(ctx: GraphContext, args: dict[str, str], key: str) -> dict[str, str]:
    """Each argument of ``args`` (robot.yaml's ``key``) given an empty value -> where it is
    written, as a warning names it: ``robot.yaml:7: source.args.prefix``."""
    from mjcfbuild.manifest.pinpoint import key_line

    empty = sorted(name for name, value in args.items() if not value.strip())
    if not empty:
        return {}
    where = {}
    for name in empty:
        setting = f"{key}.{name}"
        line = key_line(ctx.manifest_file, setting)
        label = ctx.manifest_output_label
        where[name] = f"{label}:{line}: {setting}" if line else f"{label} {setting}"
    return where


def expand_file_task(
    ctx: GraphContext,
    name: str,
    source: Path,
    kind: str,
    args: dict[str, str],
    packages: dict[str, Path],
    output: Path,
    deps: Path,
    args_at: str | None = None,
    written: str = "",
) -> dict:
    """The task expanding (xacro) or reading (URDF) ``source`` into ``output``; the files it
    read are listed in ``deps`` and checked from the next build on, where each line's element
    was written in :func:`~mjcfbuild.sources.origins.origins_file`. ``args_at`` is the
    robot.yaml key giving ``args`` (``source.args``), for the messages about them; ``written``,
    the source's path as robot.yaml writes it, for the hint that names it as xacro."""
    from mjcfbuild.sources.origins import origins_file

    read, stale = discovered_inputs(ctx, deps)
    payload = ExpandPayload(
        kind=kind,
        source=str(source),
        args=args,
        packages=package_folders(packages),
        environment=ros_environment(ctx),
        package_index=ros_package_index(ctx),
        output=str(output),
        depfile=str(deps),
        origins=str(origins_file(output)),
        args_key=_args_key(ctx, args_at) if args_at else "",
        empty_args=_empty_args(ctx, args, args_at) if args_at else {},
        base_dir=str(ctx.base_dir),
        written=written,
    )
    return file_task(
        ctx,
        FAMILY,
        name,
        f"expand {ctx.label(source)}",
        payload,
        in_worker=kind == "xacro",
        file_dep=[source, *read],
        targets=[output, deps, origins_file(output)],
        extra_uptodate=stale,
    )


FAMILY = Family(
    name="expand",
    step="mjcfbuild.steps.expand:run",
    payload=ExpandPayload,
    # 2: the origins of the expanded lines; 3: xacro.arg reads and files not UTF-8 as xacro
    # takes them; 4: the patterns xacro includes list, with their files
    format=5,  # 5: args stripped and empty ones ignored as the xacro command does; its warnings
    tools=("xacro",),
    tasks=_tasks,
    stage="planning",
)
