"""``mjcfbuild build``: build the models of manifests, doing only what changed."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

from mjcfbuild.cli import (
    environment_jobs,
    jobs_argument,
    load_context,
    report_error,
    report_warning,
    timeout_argument,
)
from mjcfbuild.errors import EXIT_OK, MjcfbuildError

if TYPE_CHECKING:
    from mjcfbuild.engine.workers import WorkerPool


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "build",
        help="build the models described by manifests (robot.yaml)",
        description="Build the model of each manifest. Only tasks whose inputs changed run.",
    )
    parser.add_argument(
        "manifests",
        nargs="*",
        default=["robot.yaml"],
        metavar="MANIFEST",
        help="manifests to build (default: robot.yaml)",
    )
    jobs_argument(parser)
    timeout_argument(parser)
    parser.add_argument("-q", "--quiet", action="store_true", help="print only warnings and errors")
    parser.add_argument(
        "-v",
        "--verbose",
        action="store_true",
        help="also say why resident workers are off, when they are",
    )
    parser.add_argument(
        "--no-check", action="store_true", help="skip the check against the URDF (and previews)"
    )
    parser.add_argument(
        "--no-remote",
        action="store_true",
        help="do not use the remote cache (cache.remote, $MJCFBUILD_CACHE_REMOTE) in this build",
    )
    parser.add_argument(
        "--executor",
        metavar="ADDRESS",
        help="where mesh conversions and decompositions run: local, or dask://host:port "
        "(default: $MJCFBUILD_EXECUTOR, else robot.yaml's executor, else local)",
    )
    parser.add_argument(
        "-n", "--dry-run", action="store_true", help="say what would run, and why; run nothing"
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Build every manifest; the exit code of the first that failed."""
    code = EXIT_OK
    if args.verbose and not args.quiet:
        _say_why_workers_are_off()
    for manifest in args.manifests:
        if not args.dry_run and _nothing_changed(manifest, args):
            continue
        workers = None if args.dry_run else _start_workers(manifest, args)
        try:
            ctx = load_context(manifest, args)
            ctx = replace(ctx, noop_stamp=ctx.manifest.source.description != "-")
            if args.dry_run:
                result = dry_run(ctx)
            else:
                result = execute(ctx, args.quiet, args.debug, workers=workers)
        except MjcfbuildError as error:
            report_error(error, args.debug)
            result = error.exit_code
        finally:
            if workers is not None:
                workers.close()  # the build closed them already, unless it never started
        code = code or result
    return code


def _say_why_workers_are_off() -> None:
    """Print, once, why builds here start their own workers instead of resident ones."""
    import os

    from mjcfbuild.engine.resident import off_reason

    reason = off_reason(os.environ)
    if reason is not None:
        print(f"mjcfbuild: resident workers are off: {reason}")


def _start_workers(manifest: str, args: argparse.Namespace) -> WorkerPool | None:
    """Workers for the rebuild of ``manifest``, started before it is read (engine.early)."""
    from mjcfbuild.engine.context import default_jobs
    from mjcfbuild.engine.early import start_workers

    jobs = args.jobs or environment_jobs() or default_jobs()
    return start_workers(manifest, run_check=not args.no_check, jobs=jobs)


def _nothing_changed(manifest: str, args: argparse.Namespace) -> bool:
    """Whether the no-op fast path found nothing to do (and said so, as a build would)."""
    import time

    from mjcfbuild.engine import stamp

    started = time.perf_counter()
    summary = stamp.nothing_to_do(manifest, run_check=not args.no_check)
    if summary is None:
        return False
    if not args.quiet:
        seconds = time.perf_counter() - started
        print(
            f"mjcfbuild: built {summary['robot']}: 0 run, {summary['tasks']} up to date "
            f"in {seconds:.2f} s"
        )
    return True


def execute(
    ctx,
    quiet: bool,
    debug: bool,
    hints: Callable[[str], str] | None = None,
    workers: WorkerPool | None = None,
) -> int:
    """Run a build of ``ctx`` and print its warnings, errors and summary; the exit code.

    ``hints`` rewrites the advice errors give (``convert`` has flags where robot.yaml has keys);
    ``workers`` were started for this build before its manifest was read.
    """
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import run_build

    def report(error: MjcfbuildError) -> None:
        if hints is not None and error.hint:
            error.hint = hints(error.hint)
        report_error(error, debug, base_dir=ctx.base_dir)

    try:
        result = run_build(ctx, Progress(quiet=quiet), workers)
    except MjcfbuildError as error:  # found while making the graph (missing source, ...)
        report(error)
        return error.exit_code
    for warning in result.warnings:
        report_warning(warning)
    for failure in result.errors:
        report(failure)
    if debug and result.engine_log.strip():
        print(result.engine_log, file=sys.stderr)
    if not quiet or result.errors:
        print(result.summary())
        if result.slowest and result.seconds > 2.0 and not quiet:
            slowest = ", ".join(f"{title} {seconds:.2f} s" for title, seconds in result.slowest)
            print(f"  slowest: {slowest}")
    return result.errors[0].exit_code if result.errors else EXIT_OK


def dry_run(ctx) -> int:
    """Print what a build would run and why."""
    from mjcfbuild.engine.status import build_statuses

    statuses, complete = build_statuses(ctx)
    running = [s for s in statuses if not s.up_to_date]
    for status in running:
        print(f"would run: {status.title}: {'; '.join(status.reasons)}")
    if not complete:
        print("  (the plan would be made again first; the tasks after it follow from it)")
    print(
        f"mjcfbuild: {ctx.manifest.robot_file}: {len(running)} would run, "
        f"{len(statuses) - len(running)} up to date (dry run)"
    )
    return EXIT_OK
