"""``mjcfbuild build``: build the models of manifests, doing only what changed."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.cli import (
    allow_outside_argument,
    chosen_manifests,
    jobs_argument,
    load_context,
    manifest_argument,
    timeout_argument,
)
from mjcfbuild.console import report_error, report_warnings
from mjcfbuild.errors import EXIT_OK, CheckError, MjcfbuildError

if TYPE_CHECKING:
    from mjcfbuild.engine.workers import WorkerPool


# How a build's summary says to see each check; `convert` has no manifest to name.
CHECK_COMMAND = "mjcfbuild check"


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "build",
        help="build the models described by manifests (robot.yaml)",
        description="Build the model of each manifest. Only tasks whose inputs changed run.",
    )
    build_options(parser)
    parser.add_argument(
        "-n", "--dry-run", action="store_true", help="say what would run, and why; run nothing"
    )
    parser.add_argument(
        "--fail-on-change",
        action="store_true",
        help="exit 6 when the build created or changed a published file (model, scene, "
        "assets, report), or one is not tracked by git: the pre-commit hook's way to make "
        "you git add them",
    )
    parser.set_defaults(handler=run)


def build_options(parser: argparse.ArgumentParser) -> None:
    """The options of a build, which ``build`` and ``watch`` share: manifests, jobs, time
    limit, output folder, check, remote cache and executor."""
    manifest_argument(parser, several=True)
    jobs_argument(parser)
    timeout_argument(parser)
    allow_outside_argument(parser)
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


def run(args: argparse.Namespace) -> int:
    """Build every manifest; the exit code of the first that failed."""
    code = EXIT_OK
    if args.verbose and not args.quiet:
        say_why_workers_are_off()
    for manifest in chosen_manifests(args):
        result = build_manifest(manifest, args)
        code = code or result
    return code


def build_manifest(manifest: str, args: argparse.Namespace) -> int:
    """Build one manifest as ``mjcfbuild build`` does (the no-op fast path first); its exit
    code, with any error printed."""
    if not args.dry_run:
        summary = _nothing_changed(manifest, args)
        if summary is not None:
            if args.fail_on_change:  # nothing created or changed; added?
                published = summary.get("outputs", [])
                return _report_unadded([], [], published, args.debug)
            return EXIT_OK
    workers = None if args.dry_run else _start_workers(manifest, args)
    try:
        ctx = load_context(manifest, args)
        ctx = replace(ctx, noop_stamp=ctx.manifest.source.description != "-")
        if args.dry_run:
            return dry_run(ctx)
        if args.fail_on_change:
            return _build_and_compare(ctx, args, workers)
        return execute(ctx, args.quiet, args.debug, workers=workers)
    except MjcfbuildError as error:
        report_error(error, args.debug)
        return error.exit_code
    finally:
        if workers is not None:
            workers.close()  # the build closed them already, unless it never started


def say_why_workers_are_off() -> None:
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

    jobs = args.jobs or default_jobs()
    return start_workers(manifest, run_check=not args.no_check, jobs=jobs)


def _nothing_changed(manifest: str, args: argparse.Namespace) -> dict | None:
    """The stamp's summary when the no-op fast path found nothing to do (and said so, as a
    build would), else None."""
    from mjcfbuild.engine import stamp

    found: list[dict] = []

    def check() -> dict | None:
        summary = stamp.nothing_to_do(manifest, not args.no_check, args.allow_outside)
        found.extend([summary] if summary is not None else [])
        return summary

    base_dir = Path(manifest).resolve().parent
    return found[0] if report_nothing_to_do(check, args.quiet, base_dir) else None


def report_nothing_to_do(
    check: Callable[[], dict | None],
    quiet: bool,
    base_dir: Path | None = None,
    check_command: str = CHECK_COMMAND,
) -> bool:
    """Run the no-op fast path's ``check`` (a stamp lookup); when it finds nothing to do,
    print what a build would - the model's warnings, one line per kind (their files named
    from here where they are in ``base_dir``, the manifest's folder), and the summary, with
    the ``check_command`` that checks the model again - and return True."""
    import os
    import time

    started = time.perf_counter()
    summary = check()
    if summary is None:
        return False
    if not quiet:
        warnings = summary["warnings"]
        listed_in = os.path.relpath(summary["report"]) if warnings else ""
        report_warnings(warnings, listed_in, base_dir=base_dir)
        count = len(warnings)
        counted = f", {count} warning{'s' if count > 1 else ''}" if count else ""
        seconds = time.perf_counter() - started
        print(
            f"mjcfbuild: built {summary['robot']}: 0 run, {summary['tasks']} up to date"
            f"{counted} in {seconds:.2f} s"
        )
        if "check_results" in summary:  # as the full build prints it
            results = summary["check_results"]
            print(check_line(Path(results), count, check_command) if results else NOT_CHECKED)
    return True


def _build_and_compare(ctx, args: argparse.Namespace, workers: WorkerPool | None) -> int:
    """Build ``ctx``; exit 6 if that created or changed a published file, or one is not
    tracked by git (``--fail-on-change``)."""
    from mjcfbuild.engine.published import changes, published_files, snapshot

    before = snapshot(published_files(ctx))
    code = execute(ctx, args.quiet, args.debug, workers=workers)
    after = snapshot(published_files(ctx))
    created, changed = changes(before, after)
    elsewhere = tuple(ctx.session.removed_elsewhere)  # in an earlier output folder
    return code or _report_unadded(created, changed, list(after), args.debug, elsewhere)


def _report_unadded(
    created: list[str],
    changed: list[str],
    published: list[str],
    debug: bool,
    removed_elsewhere: tuple[str, ...] = (),
) -> int:
    """Report files the build created or changed, published files git does not track, and
    removed ones git still has (in the folders of ``published`` and ``removed_elsewhere``);
    the exit code (6 if there are any)."""
    import os

    from mjcfbuild.engine.published import (
        git_deleted,
        git_removed,
        git_status,
        in_work_tree,
        unstaged,
    )
    from mjcfbuild.errors import CheckError

    untracked, ignored = git_status(published)
    in_git = bool(published) and in_work_tree(os.path.dirname(published[0]))
    written = (set(created) | set(changed)) - ignored
    tracked = written - untracked
    differing = unstaged(sorted(tracked)) if in_git and tracked else None
    if differing is not None:  # written as git has them staged (after a clean, a hand edit)
        written -= tracked - differing
    # The model and scene first: files at the top of the output folder, then those below.
    created = sorted(written & set(created), key=_top_first)
    changed = sorted(written & set(changed), key=_top_first)
    not_added = sorted(untracked - ignored - set(created), key=_top_first)
    removed_files = git_removed(published) | git_deleted(list(removed_elsewhere))
    removed = sorted(removed_files, key=_top_first)
    if not created and not changed and not not_added and not removed:
        return EXIT_OK
    parts = []
    for words, names in (
        ("files were created", created),
        ("files were changed", changed),
        ("files git does not track", not_added),
        ("files were removed that git still has", removed),
    ):
        if names:
            shown = [os.path.relpath(name) for name in names[:5]]
            more = f" and {len(names) - 5} more" if len(names) > 5 else ""
            parts.append(f"{words}: {', '.join(shown)}{more}")
    hint = (
        "git add them, then commit again"  # git add stages a removal too
        if in_git
        else "not in a git work tree: --fail-on-change fails on any file a build writes anew"
    )
    error = CheckError("; ".join(parts), hint=hint)
    report_error(error, debug)
    return error.exit_code


def execute(
    ctx,
    quiet: bool,
    debug: bool,
    hints: Callable[[str], str] | None = None,
    workers: WorkerPool | None = None,
    warnings: list[str] | None = None,
    files: Callable[[str], str] | None = None,
    check_command: str = CHECK_COMMAND,
) -> int:
    """Run a build of ``ctx`` and print its errors, summary and (unless ``quiet``) warnings,
    one line per kind; the exit code. The summary's check line names ``check_command``.

    ``hints`` rewrites the advice errors give (``convert`` has flags where robot.yaml has keys);
    ``files`` the files they name (``diff``: a revision's copy as ``<revision>:<path>``);
    ``workers`` were started for this build before its manifest was read; ``warnings``, when
    given, receives the warnings instead of the console (``diff`` prints them after its answer).
    """
    from mjcfbuild import interrupts
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import run_build

    def report(error: MjcfbuildError) -> None:
        if hints is not None and error.hint:
            error.hint = hints(error.hint)
        if files is not None and error.location is not None:
            error.relocate(ctx.base_dir, Path.cwd())
            error.location.file = files(error.location.file)
            report_error(error, debug)
        else:
            report_error(error, debug, base_dir=ctx.base_dir)

    try:
        result = run_build(ctx, Progress(quiet=quiet), workers)
    except MjcfbuildError as error:  # found while making the graph (missing source, ...)
        report(error)
        return error.exit_code
    if warnings is not None:
        warnings.extend(result.warnings)
    elif not quiet:
        # The report is written when the model was (a failed check still leaves one).
        built = all(isinstance(error, CheckError) for error in result.errors)
        report_warnings(result.warnings, report_md(ctx) if built else "", base_dir=ctx.base_dir)
    for failure in result.errors:
        report(failure)
    if debug and result.engine_log.strip():
        print(result.engine_log, file=sys.stderr)
    if not quiet:
        interrupts.check()  # a SIGINT while the warnings printed: no line saying "built"
        print(result.summary())
        if result.slowest and result.seconds > 2.0:
            slowest = ", ".join(f"{title} {seconds:.2f} s" for title, seconds in result.slowest)
            print(f"  slowest: {slowest}")
        if not result.errors:
            print(_check_line(ctx, len(result.warnings), check_command))
    return result.errors[0].exit_code if result.errors else EXIT_OK


def _check_line(ctx, warnings: int, check_command: str) -> str:
    """The check's verdict under a build's summary, as ``mjcfbuild check`` gives it, or that
    the build did not check."""
    from mjcfbuild.outputs import CHECK_RESULTS

    if not ctx.run_check:
        return NOT_CHECKED
    return check_line(ctx.state(CHECK_RESULTS), warnings, check_command)


NOT_CHECKED = "  check: not run (--no-check); `mjcfbuild check` runs it"


def check_line(results: Path, warnings: int = 0, check_command: str = CHECK_COMMAND) -> str:
    """The line under a build's summary for the check results in ``results`` (check.json),
    with the build's ``warnings`` (as many as its summary counts) where the checks found none
    to say (the report's verdict counts both), and the command that shows each check."""
    import json

    try:
        verdict = json.loads(results.read_bytes())["verdict"]
    except (OSError, ValueError, KeyError, TypeError):
        return "  check: no results (`mjcfbuild check` runs it)"
    if verdict == "check passed" or verdict.startswith("checks pass with "):
        verdict = (
            f"checks pass with the {warnings} warning{'s' if warnings > 1 else ''} above"
            if warnings
            else "all checks pass"
        )
    return f"  check: {verdict} (each check: `{check_command}`)"


def report_md(ctx) -> str:
    """Where a build's report lists every warning, as the console names it."""
    import os

    from mjcfbuild.outputs import report_dir

    return os.path.relpath(report_dir(ctx) / "report.md")


def dry_run(ctx) -> int:
    """Print what a build would run and why (or the error the build would stop with, where
    it may not write its output folder)."""
    from mjcfbuild.engine.guard import check_output_folder
    from mjcfbuild.engine.status import build_statuses

    check_output_folder(ctx)
    statuses, complete = build_statuses(ctx)
    running = [s for s in statuses if not s.up_to_date]
    for status in running:
        print(f"would run: {status.title}: {'; '.join(status.reasons)}")
    then = list(dict.fromkeys(title for status in running for title in status.then))
    if then:  # doit decides each once the task before it has run: by what it wrote
        print(f"  then, where what it writes comes out changed: {', '.join(then)}")
    if not complete:
        print("  (the plan would be made again first; the tasks after it follow from it)")
    print(
        f"mjcfbuild: {ctx.manifest.robot_file}: {len(running)} would run, "
        f"{len(statuses) - len(running)} up to date (dry run)"
    )
    return EXIT_OK


def _top_first(name: str) -> tuple[int, str]:
    import os

    return name.count(os.sep), name
