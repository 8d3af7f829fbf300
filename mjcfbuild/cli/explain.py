"""``mjcfbuild explain``: why each task would run (which input, parameter or output changed)."""

from __future__ import annotations

import argparse
import os

from mjcfbuild.cli import (
    DEFAULT_MANIFEST,
    chosen_manifest,
    load_context,
    looks_like_manifest,
    manifest_argument,
)
from mjcfbuild.errors import EXIT_OK, UsageError


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "explain",
        help="say why tasks would run: which input, parameter or output changed",
        description="Say, for every task (or one), whether it is up to date and if not, why.",
    )
    # Two optional positionals, told apart by what they look like, not by their order.
    parser.add_argument(
        "first",
        nargs="?",
        metavar="MANIFEST",
        help="the manifest (default: robot.yaml): a word ending in .yaml or .yml, or naming "
        "a file; it may come after the task",
    )
    parser.add_argument("second", nargs="?", metavar="TASK", help="a task, like mesh:base")
    manifest_argument(parser, positional=False)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the statuses."""
    from mjcfbuild.engine.status import build_statuses

    words = [word for word in (args.first, args.second) if word is not None]
    manifest, args.task = _manifest_and_task(words, named=args.manifest_flag is not None)
    ctx = load_context(chosen_manifest(args, manifest), args)
    statuses, complete = build_statuses(ctx)
    if args.task:
        chosen = [s for s in statuses if s.name == args.task or s.title == args.task]
        if not chosen:
            from mjcfbuild.sources.packages import did_you_mean

            known = [s.name for s in statuses]
            names = ", ".join(known)
            hint = "" if complete else " (the plan must be made again before later tasks exist)"
            mean = did_you_mean(args.task, known)
            raise UsageError(f"no task '{args.task}'{mean or ';'} tasks: {names}{hint}")
        statuses = chosen
    for status in statuses:
        if status.up_to_date:
            print(f"{status.name}: up to date")
        else:
            print(f"{status.name}: would run")
            for reason in status.reasons:
                print(f"  - {reason}")
            if status.then:  # doit decides each once this one ran: by what it wrote
                print(f"  then, where what it writes comes out changed: {', '.join(status.then)}")
    if not complete and not args.task:
        print("(later tasks are known once the plan is made again: run mjcfbuild build)")
    return EXIT_OK


def _manifest_and_task(words: list[str], named: bool = False) -> tuple[str | None, str | None]:
    """Sort ``explain``'s positional words into the manifest and the task name; ``named``:
    ``-m`` names the manifest."""
    manifests = [word for word in words if looks_like_manifest(word)]
    tasks = [word for word in words if not looks_like_manifest(word)]
    folders = [word for word in tasks if os.path.isdir(word)]
    # A folder given for the manifest, as build, check, graph and clean are given one: the
    # manifest (which loading refuses in the same words), unless it can be a task of the
    # robot.yaml here (a task named like a folder: check, previews).
    can_be_task = len(tasks) == 1 and os.path.exists(DEFAULT_MANIFEST)
    if folders and not manifests and not named and not can_be_task:
        manifests = folders[:1]
        tasks.remove(folders[0])
    if len(manifests) > 1 or len(tasks) > 1:
        raise UsageError(
            f"explain takes one manifest and one task at most, not {' '.join(words)}",
            hint="a word ending in .yaml or .yml, or naming a file, is the manifest",
        )
    return (manifests[0] if manifests else None), (tasks[0] if tasks else None)
