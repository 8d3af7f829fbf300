"""``mjcfbuild clean``: remove what builds wrote (models, assets, report, build state), and
nothing else."""

from __future__ import annotations

import argparse
import contextlib
import os
import shutil
from pathlib import Path

from mjcfbuild.cli import (
    allow_outside_argument,
    chosen_manifest,
    load_context,
    manifest_argument,
    timeout_argument,
)
from mjcfbuild.console import report_warning
from mjcfbuild.errors import EXIT_OK
from mjcfbuild.failpoints import failpoint

_SHOWN = 5  # files named in a line before "and N more"


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "clean",
        help="remove the built model, its assets, report and build state",
        description=(
            "Remove the files builds wrote into the output folder (the robot and scene files, "
            "what they wrote in assets/, report/ and the other folders, and .mjcfbuild/), as "
            "builds recorded them, and the folders that leave empty. Files builds did not write, "
            "and files they wrote that were edited since, are left alone and named; links are "
            "not followed, and neither is the shared cache touched (see mjcfbuild cache)."
        ),
    )
    manifest_argument(parser)
    parser.add_argument(
        "-n", "--dry-run", action="store_true", help="list what would be removed; remove nothing"
    )
    allow_outside_argument(parser)
    timeout_argument(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Remove the recorded outputs, or list them (``--dry-run``)."""
    from mjcfbuild.engine import written
    from mjcfbuild.engine.guard import check_output_folder, check_owner
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import build_lock

    ctx = load_context(chosen_manifest(args), args)
    out = ctx.out_dir
    check_output_folder(ctx)
    if not out.is_dir() or not ctx.state_dir.is_dir():
        _say(args, "removed nothing" if not args.dry_run else "would remove nothing")
        return EXIT_OK
    check_owner(ctx)  # another robot.yaml's folder: its files are not this one's to remove
    names = written.recorded(ctx)
    if names is None:
        report_warning(
            f"{ctx.label(ctx.state_dir)}: no record of the files builds wrote here (an older "
            "mjcfbuild built it); build once, then clean again"
        )
        _say(args, "removed nothing" if not args.dry_run else "would remove nothing")
        return EXIT_OK
    present = [name for name in names if written.written_file(out, name)]
    # A file the user edited since the build wrote it is theirs now.
    edited = [out / name for name in present if written.edited(out, name, names[name])]
    # The package's changelog holds every earlier build's entry and the user's notes between
    # them (a rebuild keeps them, as its own bytes): no build can write it again.
    from mjcfbuild.outputs import PACKAGE_CHANGELOG, PACKAGE_FOLDER

    changelog = f"{PACKAGE_FOLDER}/{PACKAGE_CHANGELOG}"
    history = [out / name for name in present if name == changelog and out / name not in edited]
    files = [out / name for name in present if out / name not in {*edited, *history}]
    if args.dry_run:  # the list is the answer asked for: -q leaves out the rest
        print("mjcfbuild: would remove:")
        for path in [*files, ctx.state_dir]:
            print(f"  {ctx.label(path)}{'/' if path == ctx.state_dir else ''}")
        if not args.quiet:
            _say_edited(ctx, edited)
            _say_history(ctx, history)
            _say_kept(ctx, {*files, *edited, *history})
        return EXIT_OK
    with build_lock(ctx, Progress(quiet=True)):
        for path in files:
            path.unlink(missing_ok=True)
        _remove_empty_folders(out, list(names))
        # Still holding the lock: a build waiting for it finds the folder gone and makes a
        # new one, never loses the state it has just made (the guard refused a link there).
        shutil.rmtree(ctx.state_dir, ignore_errors=True)
        # The files kept as edited are the user's now: the next build, finding no record of
        # its own, must not take them for a fresh clone's outputs and write over them. (The
        # changelog, which builds extend around the user's notes, stays the build's.)
        yours = [path for path in edited if path.relative_to(out).as_posix() != changelog]
        if yours:
            from mjcfbuild.ownership import record_foreign

            ctx.state_dir.mkdir()
            record_foreign(out, (), [path.relative_to(out).as_posix() for path in yours])
        if not out.is_symlink() and not any(out.iterdir()):  # a linked folder is the user's
            with contextlib.suppress(OSError):  # a waiting build made its state folder again
                out.rmdir()
        failpoint("clean-removed")  # the tests stop here, the lock still held
    from mjcfbuild.engine.outputs_off import grouped_files

    _say(args, "removed " + ", ".join([*grouped_files(ctx, files), _state_removed(ctx, yours)]))
    if out.is_dir() and not args.quiet:
        _say_edited(ctx, edited)
        _say_history(ctx, history)
        _say_kept(ctx, {*edited, *history})
    return EXIT_OK


def _say(args: argparse.Namespace, text: str) -> None:
    """Print ``text``, unless -q asks for quiet: what was removed (not what would be, with
    --dry-run, which is the answer asked for)."""
    if not args.quiet or args.dry_run:
        print(f"mjcfbuild: {text}")


def _remove_empty_folders(out: Path, names: list[str]) -> None:
    """Remove the folders of recorded files that are empty now, deepest first; never through
    a link, never the output folder itself (the caller decides)."""
    folders = {
        "/".join(name.split("/")[:depth])
        for name in names
        for depth in range(1, name.count("/") + 1)
    }
    for folder in sorted(folders, key=lambda f: f.count("/"), reverse=True):
        path = out / folder
        if not path.is_symlink() and path.is_dir() and not any(path.iterdir()):
            path.rmdir()


def _state_removed(ctx, yours: list[Path]) -> str:
    """How the removal line names the build state: its folder, gone; or, where clean
    recorded the edited files it kept as the user's, what stays in it and why."""
    state = ctx.label(ctx.state_dir) + "/"
    if not yours:  # gone (or made again by a build that waited for clean: its own, not ours)
        return state
    from mjcfbuild.ownership import FOREIGN

    them = "it" if len(yours) == 1 else "them"
    return (
        f"the build state in {state} (but for {FOREIGN}, which records the edited "
        f"file{'s' if len(yours) > 1 else ''} kept as yours, so that no build writes over {them})"
    )


def _say_edited(ctx, edited: list[Path]) -> None:
    """Name every file a build wrote that the user edited since, which stays (recorded as
    the user's, which no build writes over: mjcfbuild.ownership)."""
    for path in edited:
        print(f"mjcfbuild: kept {ctx.label(path)} (edited since mjcfbuild wrote it)")


def _say_history(ctx, history: list[Path]) -> None:
    """Name the changelog clean keeps."""
    for path in history:
        print(
            f"mjcfbuild: kept {ctx.label(path)} (the history of earlier builds: no build can "
            "write it again; remove it yourself if it is to go)"
        )


def _say_kept(ctx, listed: set[Path]) -> None:
    """Name the files left in the output folder that no build wrote, a few of them (those in
    ``listed`` are named already)."""
    from mjcfbuild.engine.guard import build_folders

    # Where the output folder is the description's own (output.folder: .), its files are the
    # description, not files left beside a model: only the folders builds fill are looked at.
    own = ctx.manifest_file is not None and ctx.out_dir in ctx.manifest_file.parents
    folders = [f for f in build_folders(ctx) if f != ctx.state_dir] if own else [ctx.out_dir]
    kept = sorted(
        {
            path
            for folder in folders
            for path in (_files_below(folder) if folder.is_dir() else [])
            if path not in listed
            and ctx.state_dir not in path.parents
            and ".git" not in path.relative_to(ctx.out_dir).parts
        }
    )
    if kept:
        shown = ", ".join(ctx.label(path) for path in kept[:_SHOWN])
        more = f" and {len(kept) - _SHOWN} more" if len(kept) > _SHOWN else ""
        print(f"mjcfbuild: kept {shown}{more} (not written by mjcfbuild)")


def _files_below(folder: Path) -> list[Path]:
    """Every file and link below ``folder``, sorted, not following links to folders."""
    found = []
    for root, dirs, names in os.walk(folder):  # os.walk does not enter linked folders
        found += [Path(root) / name for name in names]
        found += [Path(root) / name for name in dirs if (Path(root) / name).is_symlink()]
    return sorted(found)
