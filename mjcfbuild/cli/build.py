"""``mjcfbuild build``: build the model of a manifest, doing only what changed."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from mjcfbuild.cli import (
    environment_jobs,
    jobs_argument,
    report_error,
    report_warning,
    step_timeout,
    timeout_argument,
)
from mjcfbuild.errors import EXIT_OK, ManifestError


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "build",
        help="build the model described by a manifest (robot.yaml)",
        description="Build the model described by a manifest. Only tasks whose inputs changed run.",
    )
    parser.add_argument(
        "manifest", nargs="?", default="robot.yaml", help="the manifest (default: robot.yaml)"
    )
    jobs_argument(parser)
    timeout_argument(parser)
    parser.add_argument("-q", "--quiet", action="store_true", help="print only warnings and errors")
    parser.add_argument(
        "--no-check", action="store_true", help="skip the check against the URDF (and previews)"
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Build and report."""
    from mjcfbuild.engine.context import BuildContext, default_jobs

    path = Path(args.manifest)
    jobs = args.jobs or environment_jobs() or default_jobs()
    try:
        ctx = BuildContext.from_manifest_file(path, jobs=jobs, step_timeout=step_timeout(args))
        ctx.run_check = not args.no_check
    except ManifestError as error:
        report_error(error, args.debug, base_dir=path.resolve().parent)
        return error.exit_code
    return execute(ctx, quiet=args.quiet, debug=args.debug)


def execute(ctx, quiet: bool, debug: bool) -> int:
    """Run a build of ``ctx`` and print its warnings, errors and summary; the exit code."""
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import run_build

    try:
        result = run_build(ctx, Progress(quiet=quiet))
    except Exception as error:  # errors found while making the graph (missing source, ...)
        from mjcfbuild.errors import MjcfbuildError

        if isinstance(error, MjcfbuildError):
            report_error(error, debug, base_dir=ctx.base_dir)
            return error.exit_code
        raise
    for warning in result.warnings:
        report_warning(warning)
    for error in result.errors:
        report_error(error, debug, base_dir=ctx.base_dir)
    if debug and result.engine_log.strip():
        print(result.engine_log, file=sys.stderr)
    if not quiet or result.errors:
        print(result.summary())
        if result.slowest and result.seconds > 2.0 and not quiet:
            slowest = ", ".join(f"{title} {seconds:.2f} s" for title, seconds in result.slowest)
            print(f"  slowest: {slowest}")
    return result.errors[0].exit_code if result.errors else EXIT_OK
