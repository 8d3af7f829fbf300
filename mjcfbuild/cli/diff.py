"""``mjcfbuild diff``: what changed in the model between two revisions or two build folders."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable
from pathlib import Path

from mjcfbuild.cli import (
    allow_outside_argument,
    chosen_manifest,
    jobs_argument,
    manifest_argument,
    timeout_argument,
)
from mjcfbuild.errors import EXIT_CHECK, EXIT_OK, MjcfbuildError, UsageError

FORMATS = ("text", "markdown", "json")


class RevisionBuildFailed(MjcfbuildError):
    """One side of the diff did not build (its build said why); exits with the build's code."""

    def __init__(self, label: str, code: int) -> None:
        super().__init__(
            f"{label} did not build, so there is no model to compare",
            hint="fix the error above, or diff revisions that build",
        )
        self.exit_code = code


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "diff",
        help="say what changed in the model between two git revisions or two build folders",
        description=(
            "Build two revisions of the description repo (each incrementally, in a scratch "
            "folder of its own, sharing the mesh cache) and say what changed in the MODEL: "
            "bodies and joints, kinematics, masses, joint limits, actuators, collision "
            "geometry and matrix, home pose, check results and preview pictures. "
            "--head defaults to the working tree, built in its own output folder."
        ),
    )
    manifest_argument(parser)
    parser.add_argument("--base", metavar="REF", help="the git revision to compare against")
    parser.add_argument(
        "--head", metavar="REF", help="the git revision to compare (default: the working tree)"
    )
    parser.add_argument(
        "--folders",
        nargs=2,
        metavar=("OLD", "NEW"),
        help="compare two output folders mjcfbuild build wrote, building nothing",
    )
    parser.add_argument(
        "--format", choices=FORMATS, default="text", help="what to print (default: text)"
    )
    parser.add_argument(
        "--write",
        metavar="FOLDER",
        help="also write diff.md, diff.json and the changed pictures side by side there, and "
        "(where the new side has output.page) its report page with the changes, index.html",
    )
    parser.add_argument(
        "--scratch",
        metavar="FOLDER",
        help="where revisions are checked out and built "
        "(default: the user cache folder's diff/<repo>)",
    )
    jobs_argument(parser)
    timeout_argument(parser)
    allow_outside_argument(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Build or find both sides, compare them, print the diff."""
    from mjcfbuild.diff.compare import compare
    from mjcfbuild.diff.snapshot import read_snapshot

    warnings: dict[str, list[str]] = {}  # each built side's warnings, printed after the answer
    sides = _sides(args, warnings)
    before = read_snapshot(sides.base_folder)
    after = read_snapshot(sides.head_folder)
    diff = compare(before, after)
    _print(diff, sides, args.format)
    if args.write:
        _write(diff, sides, Path(args.write), args.quiet)
    if not args.quiet:
        _print_warnings(warnings)
    return EXIT_OK


def _print_warnings(warnings: dict[str, list[str]]) -> None:
    """Each side's warnings, one line per kind; once for both where the sides agree."""
    from mjcfbuild.console import report_warnings

    sides = [(label, found) for label, found in warnings.items() if found]
    if len(sides) == 2:
        # What both sides warn of once, under both names; then what each warns of alone.
        (first, mine), (second, theirs) = sides
        common = [warning for warning in mine if warning in theirs]
        sides = [
            (f"{first} and {second}", common),
            (first, [warning for warning in mine if warning not in common]),
            (second, [warning for warning in theirs if warning not in common]),
        ]
    for label, found in sides:
        if found:
            report_warnings(found, prefix=f"{label}: ")


def _sides(args: argparse.Namespace, warnings: dict[str, list[str]]):
    from mjcfbuild.diff.render import Sides
    from mjcfbuild.diff.snapshot import find_model

    if args.folders:
        if args.base or args.head:
            raise UsageError("--folders compares two build folders: leave out --base and --head")
        old, new = (Path(folder) for folder in args.folders)
        base_model = find_model(old).name
        model = find_model(new).name
        return Sides(str(old), str(new), old, new, model, base_model)
    if not args.base:
        raise UsageError(
            "say what to compare: --base REF [--head REF], or --folders OLD NEW",
            hint="mjcfbuild diff --base origin/main",
        )
    return _revisions(args, warnings)


def _revisions(args: argparse.Namespace, warnings: dict[str, list[str]]):
    from mjcfbuild.cachedir import diff_cache_dir
    from mjcfbuild.diff import revisions
    from mjcfbuild.diff.render import Sides
    from mjcfbuild.diff.snapshot import find_model

    manifest = Path(chosen_manifest(args))
    repo = revisions.repository(manifest)
    base = revisions.resolve(repo, args.base)
    head = revisions.resolve(repo, args.head) if args.head else None
    scratch = Path(args.scratch) if args.scratch else diff_cache_dir() / repo.key
    base_folder = _build_revision(repo, base, scratch / "base", args, warnings)
    if head is None:
        head_folder = _build(manifest, None, "the working tree", args, warnings)
        head_label = "working tree"
    elif head.commit == base.commit:
        head_folder, head_label = base_folder, head.label
    else:
        head_folder = _build_revision(repo, head, scratch / "head", args, warnings)
        head_label = head.label
    model = find_model(head_folder).name
    base_model = find_model(base_folder).name
    return Sides(base.label, head_label, base_folder, head_folder, model, base_model)


def _build_revision(
    repo, revision, side: Path, args: argparse.Namespace, warnings: dict[str, list[str]]
) -> Path:
    from mjcfbuild.diff.revisions import extract

    manifest = extract(repo, revision, side)
    copy = str(side / "src") + os.sep

    def in_revision(file: str) -> str:
        """A file of the revision's copy as git names it (``git show 0123abcdef:urdf/a.xacro``
        shows it)."""
        if not file.startswith(copy):
            return file
        return f"{revision.commit[:10]}:{file.removeprefix(copy)}"

    return _build(manifest, side / "out", revision.label, args, warnings, in_revision)


def _build(
    manifest: Path,
    output: Path | None,
    label: str,
    args: argparse.Namespace,
    warnings: dict[str, list[str]],
    files: Callable[[str], str] | None = None,
) -> Path:
    """Build ``manifest`` (into ``output`` when given) with its messages on stderr (the files
    they name shown by ``files``), its warnings into ``warnings[label]``; its output folder. A
    check that fails still leaves a model to compare."""
    import contextlib
    from dataclasses import replace

    from mjcfbuild.cli import load_context
    from mjcfbuild.cli.build import execute

    if not args.quiet:
        print(f"mjcfbuild diff: building {label}", file=sys.stderr)
    ctx = load_context(manifest, args)
    if output is not None:
        ctx = replace(ctx, output_override=output)
    with contextlib.redirect_stdout(sys.stderr):
        code = execute(
            ctx, quiet=True, debug=args.debug, warnings=warnings.setdefault(label, []), files=files
        )
    if code not in (EXIT_OK, EXIT_CHECK):
        raise RevisionBuildFailed(label, code)
    return ctx.out_dir


def _print(diff, sides, form: str) -> None:
    from mjcfbuild.diff import render

    if form == "json":
        sys.stdout.write(render.as_json(diff, sides))
    elif form == "markdown":
        sys.stdout.write(render.markdown(diff, sides))
    else:
        sys.stdout.write(render.text(diff, sides))


def _write(diff, sides, folder: Path, quiet: bool) -> None:
    from mjcfbuild.diff import render
    from mjcfbuild.diff.page import write_page
    from mjcfbuild.errors import OutputError

    try:
        folder.mkdir(parents=True, exist_ok=True)
        pictures = render.side_by_side(diff, sides, folder)
        text = render.markdown(diff, sides, pictures)
        (folder / "diff.md").write_text(text)
        (folder / "diff.json").write_text(render.as_json(diff, sides))
        if write_page(folder, sides, text) and not quiet:
            print(f"mjcfbuild diff: page {folder / 'index.html'}", file=sys.stderr)
    except OSError as error:
        raise OutputError(f"cannot write the diff: {error.strerror}", file=str(folder)) from None
