"""The output folder's guard: builds and ``clean`` write and remove only inside it, and only
inside the manifest's folder tree unless the user allowed another place.

``output.folder`` is resolved with its symbolic links; a folder that leaves the tree of
robot.yaml's folder is refused unless ``output.allow_outside: true`` or ``--allow-outside``
says it is meant. The folders a build writes below the output folder (its state, ``assets/``,
``report/``, ...) are never written through a symbolic link, wherever it points.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import OutputError

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext

ALLOW_HINT = "set output.allow_outside: true in robot.yaml or pass --allow-outside if it is meant"


def check_output_folder(ctx: BuildContext) -> None:
    """Raise :class:`OutputError` unless the build of ``ctx`` may write its output folder."""
    if _guarded(ctx):
        _check_inside(ctx)
    for folder in build_folders(ctx):
        if folder.is_symlink():
            raise OutputError(
                f"is a symbolic link (to {os.readlink(folder)}); mjcfbuild does not write "
                "through links in its output folder",
                file=ctx.label(folder),
                hint="remove the link and let the build make the folder, or set output.folder "
                "to the folder it points at",
            )


def _guarded(ctx: BuildContext) -> bool:
    """Whether the output folder comes from robot.yaml (``convert -o``, ``diff``'s scratch
    builds and the API's folders are named by their caller)."""
    return ctx.manifest_file is not None and ctx.output_override is None


def _check_inside(ctx: BuildContext) -> None:
    if ctx.allow_outside or ctx.manifest.output.allow_outside:
        return
    tree = Path(os.path.realpath(ctx.base_dir))
    folder = Path(os.path.realpath(ctx.out_dir))
    if folder == tree or tree in folder.parents:
        return
    from mjcfbuild.manifest.pinpoint import pinpoint

    shown = ctx.manifest.output.folder
    if os.path.normpath(ctx.out_dir) != str(folder):
        where = f"'{shown}' leads through a link to {folder}"
    else:
        where = f"'{shown}'" if shown == str(folder) else f"'{shown}' ({folder})"
    error = OutputError(
        f"{where} is outside {tree}, the folder of {ctx.manifest_label}",
        file=f"{ctx.manifest_label} output.folder",
        hint=f"choose a folder inside it, or {ALLOW_HINT}",
    )
    assert ctx.manifest_file is not None, "guarded only with a manifest file"
    raise pinpoint(error, ctx.manifest_label, ctx.manifest_file)


def build_folders(ctx: BuildContext) -> list[Path]:
    """The folders below the output folder that builds write into, whether they exist or not."""
    from mjcfbuild.outputs import PACKAGE_FOLDER, report_dir

    out = ctx.out_dir
    report = report_dir(ctx)
    folders = [
        ctx.state_dir,
        ctx.assets_dir,
        report,
        report / "previews",
        report / "page",
        out / PACKAGE_FOLDER,
        out / PACKAGE_FOLDER / "assets",
    ]
    if ctx.urdf_mesh_dir is not None:
        folders.append(ctx.urdf_mesh_dir)
    from mjcfbuild.engine.written import recorded

    for name in recorded(ctx) or []:  # and those earlier builds wrote into (report/tuning, ...)
        parts = name.split("/")[:-1]
        folders += [out.joinpath(*parts[:depth]) for depth in range(1, len(parts) + 1)]
    return list(dict.fromkeys(folders))
