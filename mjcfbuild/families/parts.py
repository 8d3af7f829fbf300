"""What the task families of ``attach:`` parts share: where a part's file and packages are,
and the folders and home values they bring. The families are :mod:`mjcfbuild.families.mjcfpart`
(a task per MJCF part) and :mod:`mjcfbuild.families.compose` (URDF and xacro parts joined to
the source)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import InputError, ManifestError, MjcfbuildError
from mjcfbuild.fsutil import unreadable_file

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.manifest.composition import Attachment
    from mjcfbuild.urdf.model import Robot


def part_folders(ctx: GraphContext) -> list[Path]:
    """The folders the URDF and xacro parts read their files from: each part file's folder
    and the packages robot.yaml names for it."""
    folders: list[Path] = []
    for index, part in enumerate(ctx.manifest.attach):
        if part.source.kind != "mjcf":
            folders.append(ctx.resolve(part.source.file).parent)
            folders += part_packages(ctx, index, part).values()
    return folders


def part_source(ctx: GraphContext, index: int, part: Attachment) -> Path:
    """The part's file, refused with its robot.yaml line when it cannot be read."""
    source = ctx.resolve(part.source.file)
    problem = unreadable_file(source)
    if problem:
        raise pinpointed(
            ctx,
            InputError(  # a missing input, as a missing source is: exit 4
                f"part file {problem}",
                file=f"{ctx.manifest_label} attach[{index}].source.{part.source.kind}",
                hint="fix the path (relative to robot.yaml)",
            ),
        )
    return source


def part_packages(ctx: GraphContext, index: int, part: Attachment) -> dict[str, Path]:
    """The build's packages with the part's own over them."""
    packages = dict(ctx.resolver.explicit)
    for name, folder in sorted(part.packages.items()):
        path = ctx.resolve(folder)
        if not path.is_dir():
            raise pinpointed(
                ctx,
                ManifestError(
                    f"package '{name}' points at '{folder}', which is not a folder",
                    file=f"{ctx.manifest_label} attach[{index}].packages.{name}",
                    hint="fix the folder (relative to robot.yaml) or remove the entry",
                ),
            )
        packages[name] = path
    return packages


def pinpointed(ctx: GraphContext, error: MjcfbuildError) -> MjcfbuildError:
    """``error`` with its line in robot.yaml, where the build has a manifest file."""
    from mjcfbuild.manifest.pinpoint import pinpoint

    if ctx.manifest_file is not None:
        pinpoint(error, ctx.manifest_label, ctx.manifest_file)
    return error


def urdf_home(robot: Robot, home: dict[str, float]) -> dict[str, float]:
    """The ``home`` patterns that name joints of the URDF model (not only MJCF parts')."""
    from mjcfbuild.control.choose import matches

    moving = [joint.name for joint in robot.joints if joint.moves]
    return {
        pattern: value
        for pattern, value in home.items()
        if any(matches(name, [pattern]) for name in moving)
    }
