"""``mjcfbuild clean``: remove what a build wrote (models, assets, report, build state)."""

from __future__ import annotations

import argparse
import shutil

from mjcfbuild.cli import chosen_manifest, load_context, manifest_argument
from mjcfbuild.errors import EXIT_OK


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "clean",
        help="remove the built model, its assets, report and build state",
        description=(
            "Remove what mjcfbuild wrote into the output folder: the robot and scene files, "
            "assets/, report/ and .mjcfbuild/. Other files in the folder are left alone, and "
            "so is the shared cache (see mjcfbuild cache)."
        ),
    )
    manifest_argument(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Remove the outputs."""
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import build_lock
    from mjcfbuild.engine.tasks import report_dir

    ctx = load_context(chosen_manifest(args), args)
    removed = []
    if ctx.out_dir.is_dir():
        with build_lock(ctx, Progress(quiet=True)):
            for path in (ctx.robot_path, ctx.scene_path, ctx.urdf_path):
                if path is not None and path.exists():
                    path.unlink()
                    removed.append(ctx.label(path))
            for folder in (ctx.assets_dir, report_dir(ctx), ctx.urdf_mesh_dir):
                if folder is not None and folder.is_dir():
                    shutil.rmtree(folder)
                    removed.append(ctx.label(folder) + "/")
        shutil.rmtree(ctx.state_dir, ignore_errors=True)
        removed.append(ctx.label(ctx.state_dir) + "/")
        if not any(ctx.out_dir.iterdir()):
            ctx.out_dir.rmdir()
    if not args.quiet:
        print(f"mjcfbuild: removed {', '.join(removed) if removed else 'nothing'}")
    return EXIT_OK
