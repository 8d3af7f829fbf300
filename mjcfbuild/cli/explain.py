"""``mjcfbuild explain``: why each task would run (which input, parameter or output changed)."""

from __future__ import annotations

import argparse

from mjcfbuild.cli import load_context, manifest_option
from mjcfbuild.errors import EXIT_OK, UsageError


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "explain",
        help="say why tasks would run: which input, parameter or output changed",
        description="Say, for every task (or one), whether it is up to date and if not, why.",
    )
    parser.add_argument("task", nargs="?", help="a task name, like mesh:base or assemble")
    manifest_option(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the statuses."""
    from mjcfbuild.engine.status import build_statuses

    ctx = load_context(args.manifest, args)
    statuses, complete = build_statuses(ctx)
    if args.task:
        chosen = [s for s in statuses if s.name == args.task or s.title == args.task]
        if not chosen:
            names = ", ".join(s.name for s in statuses)
            hint = "" if complete else " (the plan must be made again before later tasks exist)"
            raise UsageError(f"no task '{args.task}'; tasks: {names}{hint}")
        statuses = chosen
    for status in statuses:
        if status.up_to_date:
            print(f"{status.name}: up to date")
        else:
            print(f"{status.name}: would run")
            for reason in status.reasons:
                print(f"  - {reason}")
    if not complete and not args.task:
        print("(later tasks are known once the plan is made again: run mjcfbuild build)")
    return EXIT_OK
