"""Where a build's warnings point: a line of a URDF the build expanded (from xacro, or joined
from ``attach:`` parts) is named where its element was written, with the expanded line after
it. The console, the no-op fast path and the report all place warnings through here, so they
name the same file and line."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.outputs import SOURCE_URDF, planned_urdf
from mjcfbuild.sources.origins import point_warning_at_source, source_location


def expanded_urdfs(ctx: BuildContext) -> list[Path]:
    """The URDFs a build makes that errors and warnings may point at: the expanded source,
    the parts' and the composed one."""
    from mjcfbuild.outputs import part_urdf

    parts = [part_urdf(ctx, index) for index in range(len(ctx.manifest.attach))]
    return [ctx.state(SOURCE_URDF), planned_urdf(ctx), *parts]


def placed_warnings(ctx: BuildContext, warnings: list[str]) -> list[str]:
    """``warnings`` placed in the source they came from, each once."""
    return list(dict.fromkeys(placed_warning(ctx, warning) for warning in warnings))


def placed_warning(ctx: BuildContext, warning: str) -> str:
    """``warning``, if it starts at a line of an expanded URDF, started instead where that
    line's element was written (the xacro file and line), the expanded line named after it."""
    for urdf in expanded_urdfs(ctx):
        warning = point_warning_at_source(warning, urdf, ctx.label(urdf), ctx.base_dir)
    return warning


def placed_location(ctx: BuildContext, where: str) -> str:
    """``where`` (``file:line``, as a check's finding names the link to fix) placed as
    :func:`placed_warning` places a warning that starts there."""
    for urdf in expanded_urdfs(ctx):
        where = source_location(where, urdf, ctx.label(urdf), ctx.base_dir)
    return where
