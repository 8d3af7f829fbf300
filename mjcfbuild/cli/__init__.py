"""The ``mjcfbuild`` command line: subcommands, error reporting and exit codes."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

from mjcfbuild.console import report_error
from mjcfbuild.errors import (
    EXIT_CODES,
    EXIT_INTERNAL,
    EXIT_OK,
    EXIT_USAGE,
    InternalError,
    MjcfbuildError,
    write_failure,
)
from mjcfbuild.version import __version__

EXAMPLES: dict[str, str] = {
    "build": "mjcfbuild build robots/arm/robot.yaml",
    "check": "mjcfbuild check robots/arm/robot.yaml",
    "explain": "mjcfbuild explain robots/arm/robot.yaml mesh:base",
    "graph": "mjcfbuild graph --dot robots/arm/robot.yaml | dot -Tsvg > graph.svg",
    "clean": "mjcfbuild clean robots/arm/robot.yaml",
    "diff": "mjcfbuild diff robots/arm/robot.yaml --base origin/main",
    "convert": "mjcfbuild convert -u robot.urdf.xacro -o mjcf_data use_gripper:=true",
    "export-urdf": "mjcfbuild export-urdf mjcf/arm.xml -o urdf/arm.urdf",
    "init": "mjcfbuild init urdf/arm.urdf.xacro --package arm_description=.",
    "schema": "mjcfbuild schema > robot.schema.json",
    "cache": "mjcfbuild cache prune --max-size 2G",
    "workers": "mjcfbuild workers stop",
    "watch": "mjcfbuild watch robots/arm/robot.yaml",
}
"""One invocation per command, shown at the end of its ``--help``."""

QUIET: dict[str, str] = {
    "build": "print errors only: no progress, warnings or summary",
    "convert": "print errors only: no progress, warnings or summary",
    "clean": "print errors only, not what was removed (--dry-run still lists what it would remove)",
    "diff": "print errors and the answer only: no building lines, warnings or page line",
    "export-urdf": "print errors only: no warnings or summary",
    "watch": "print errors only: no progress, warnings, summaries or what changed",
    "check": "print errors only: the failed checks, not the table, verdict or warnings",
    "init": "print errors only: no warnings or what was written",
}
"""What ``-q`` leaves out, per command; commands not named print only what they are asked
for already, and take ``-q`` so that it can go anywhere on a command line."""


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line, with a suggestion for a misspelling."""

    commands: dict[str, argparse.ArgumentParser]
    words: list[str]  # what it was last given to parse
    unrecognized: list[str]  # the words of those it did not take (a command's included)

    def parse_known_args(  # type: ignore[override]
        self, args: Sequence[str] | None = None, namespace: argparse.Namespace | None = None
    ) -> tuple[argparse.Namespace, list[str]]:
        """Parse as argparse does, remembering the words and those left over."""
        self.words = list(sys.argv[1:] if args is None else args)
        parsed, unrecognized = super().parse_known_args(self.words, namespace)
        self.unrecognized = list(unrecognized)
        return parsed, unrecognized

    def error(self, message: str) -> NoReturn:
        """Print ``message`` as one line with what to do, and exit with the usage code; an
        option it does not know comes first, with the closest it does (a required option
        misspelled, or a misspelled option whose value was taken for a positional argument)."""
        from mjcfbuild.cli.suggest import (
            misplaced_option,
            unknown_arguments_line,
            unknown_option,
            usage_error_line,
        )

        misuse = getattr(self, "misuse", None)  # a command's own reading of what went wrong
        problem = misuse(getattr(self, "words", [])) if misuse is not None else None
        if problem is not None:
            self.exit(EXIT_USAGE, f"mjcfbuild: error: {problem.one_line()}\n")
        misplaced = misplaced_option(self, getattr(self, "words", []))
        if misplaced is not None:  # a command's option before the command
            self.exit(EXIT_USAGE, misplaced + "\n")
        word = unknown_option(self, getattr(self, "words", []))
        if word is not None:
            self.exit(EXIT_USAGE, unknown_arguments_line(self, None, [word]) + "\n")
        self.exit(EXIT_USAGE, usage_error_line(self.prog, message) + "\n")


def build_parser() -> Parser:
    """The argument parser with every subcommand."""
    from mjcfbuild.cli import (
        build,
        cache,
        check,
        clean,
        convert,
        diff,
        explain,
        export_urdf,
        graph,
        init,
        schema,
        watch,
        workers,
    )

    parser = Parser(
        prog="mjcfbuild",
        description="Build MuJoCo models (MJCF) from URDF and xacro robot descriptions.",
        epilog=f"example: {EXAMPLES['build']}\n\nexit codes: "
        + "; ".join(f"{code} {text}" for code, text in EXIT_CODES.items()),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"mjcfbuild {__version__}")
    global_flags(parser, default=False)
    commands = parser.add_subparsers(title="commands", dest="command", metavar="COMMAND")
    commands.required = True
    commands_in_order = [build, watch, check, explain, graph, clean, convert, export_urdf, init]
    for module in (*commands_in_order, schema, diff, cache, workers):
        module.add_parser(commands)
    parser.commands = dict(commands.choices)
    for name, command in parser.commands.items():
        # After the command too; unset there, so the value given before it stands.
        global_flags(command, default=argparse.SUPPRESS, quiet=QUIET.get(name))
        command.epilog = f"example: {EXAMPLES[name]}"
    return parser


def global_flags(
    parser: argparse.ArgumentParser, default: object, quiet: str | None = None
) -> None:
    """The flags every command takes, before or after its name: ``--debug`` and ``-q``;
    ``quiet`` says what ``-q`` leaves out of this command's output."""
    parser.add_argument(
        "--debug",
        action="store_true",
        default=default,
        help="show the traceback of an error, and the build engine's output",
    )
    if quiet is None and default is argparse.SUPPRESS:
        quiet = "no effect here: this command prints only what it is asked for"
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        default=default,
        help=quiet
        or "print errors only, and the answer a command is asked for: no progress, "
        "warnings or summaries",
    )


def main(argv: Sequence[str] | None = None) -> None:
    """Run the command line and exit with its code."""
    from mjcfbuild import interrupts

    interrupts.handle_signals()  # this process is the command's: Ctrl-C and SIGTERM stop it
    try:
        code = run(argv)
    except KeyboardInterrupt:  # a second Ctrl-C while the first was being reported
        code = interrupts.exit_code()
    sys.exit(code)


def run(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit code instead of exiting."""
    from mjcfbuild import interrupts
    from mjcfbuild.cli.suggest import unknown_arguments_line

    interrupts.forget()
    words = list(sys.argv[1:] if argv is None else argv)
    if "convert" in words and "--ros-args" in words:  # launched as the reference's ROS node
        from mjcfbuild.cli.convert import without_ros_args

        words = without_ros_args(words)
    parser = build_parser()
    args, unknown = parser.parse_known_args(words)
    if unknown:
        print(unknown_arguments_line(parser, args.command, unknown), file=sys.stderr)
        return EXIT_USAGE
    try:
        if getattr(args, "jobs", 0) is None:
            # Read once, before any fast path: a bad $MJCFBUILD_JOBS is refused even when
            # nothing needs building.
            from mjcfbuild.jobs import default_jobs

            args.jobs = default_jobs()
        if args.command in CACHE_COMMANDS:
            _check_cache_settings(quiet=args.quiet)
        code: int = args.handler(args)
        interrupts.check()  # a SIGINT whose KeyboardInterrupt was lost: not a success
        return code
    except MjcfbuildError as error:
        if interrupts.received():  # an error of the stopping, after a lost KeyboardInterrupt
            return _interrupted()
        report_error(error, debug=args.debug)
        return error.exit_code
    except KeyboardInterrupt:
        return _interrupted()
    except BrokenPipeError:
        # The reader went away (`mjcfbuild graph --dot | head`): nothing left to say to it.
        # Point stdout at /dev/null so Python's final flush does not fail a second time.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_OK
    except Exception as exc:  # a bug: say so plainly, traceback only with --debug
        if interrupts.received():  # a KeyboardInterrupt Python wrapped (in a class's creation)
            return _interrupted()
        import traceback

        unwritable = write_failure(exc)  # a full disk, a folder it may not write in
        if unwritable is not None:
            report_error(unwritable, debug=args.debug, base_dir=Path.cwd())
            return unwritable.exit_code
        internal = InternalError(
            f"{type(exc).__name__}: {exc}", details="".join(traceback.format_exception(exc))
        )
        report_error(internal, debug=args.debug)
        return EXIT_INTERNAL


def _check_cache_settings(quiet: bool) -> None:
    """Refuse a bad ``$MJCFBUILD_CACHE_MAX`` (only some paths would read it), and warn once
    (unless ``quiet``) about a ``$MJCFBUILD_CACHE_DIR`` that cannot be used (every step would
    quietly store and find nothing), before any fast path."""
    from mjcfbuild.cachedir import cache_dir_problem

    if os.environ.get("MJCFBUILD_CACHE_MAX"):
        from mjcfbuild.cachedir import default_max_bytes

        default_max_bytes()
    problem = cache_dir_problem()
    if problem is not None and not quiet:
        from mjcfbuild.console import report_warning

        report_warning(problem)


CACHE_COMMANDS = frozenset({"build", "watch", "check", "convert", "diff", "cache"})
"""The commands that may read or prune the shared cache, and so its cap."""


def _interrupted() -> int:
    """Say that the command was interrupted; its exit code (130 for Ctrl-C, 143 for
    SIGTERM)."""
    from mjcfbuild import interrupts

    print("mjcfbuild: interrupted", file=sys.stderr)
    return interrupts.exit_code()


def jobs_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``-j/--jobs``."""
    parser.add_argument(
        "-j",
        "--jobs",
        type=positive_int,
        default=None,
        help="tasks to run at once (default: $MJCFBUILD_JOBS, else one per CPU)",
    )


def timeout_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--timeout``."""
    parser.add_argument(
        "--timeout",
        type=positive_seconds,
        default=None,
        metavar="SECONDS",
        help="stop a build step (mesh conversion, decomposition, assembly) that runs longer, "
        "and stop waiting for another build of the output folder after as long "
        "(default: $MJCFBUILD_TIMEOUT, else 1800)",
    )


def step_timeout(args: argparse.Namespace) -> float:
    """The step time limit from ``--timeout``, ``MJCFBUILD_TIMEOUT`` or the default."""
    from mjcfbuild.engine.context import DEFAULT_STEP_TIMEOUT
    from mjcfbuild.errors import UsageError

    if getattr(args, "timeout", None) is not None:
        return args.timeout
    value = os.environ.get("MJCFBUILD_TIMEOUT")
    if not value:
        return DEFAULT_STEP_TIMEOUT
    try:
        return positive_seconds(value)
    except argparse.ArgumentTypeError as problem:
        raise UsageError(
            f"MJCFBUILD_TIMEOUT={value}: {problem}",
            hint=f"set it to a number of seconds, or unset it for {DEFAULT_STEP_TIMEOUT:g}",
        ) from None


# The longest wait a command line may ask for (about 115 days): the system's timers refuse
# infinity and numbers near it, which failed every step of a build as an internal error.
MOST_SECONDS = 1e7


def positive_seconds(text: str) -> float:
    """An argparse type: a number of seconds more than 0 and at most :data:`MOST_SECONDS`."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds") from None
    if not value > 0:
        raise argparse.ArgumentTypeError("must be more than 0")
    if not value <= MOST_SECONDS:
        raise argparse.ArgumentTypeError(f"must be at most {MOST_SECONDS:g} (about 115 days)")
    return value


def positive_int(text: str) -> int:
    """An argparse type: a whole number of at least 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1")
    return value


def load_context(path: str | Path, args: argparse.Namespace):
    """The :class:`BuildContext` of a manifest from command-line options.

    A :class:`ManifestError` comes back with its file shown relative to the current folder.
    """
    from mjcfbuild.engine.context import BuildContext, default_jobs
    from mjcfbuild.errors import ManifestError

    path = Path(path)
    jobs = getattr(args, "jobs", None) or default_jobs()
    try:
        return BuildContext.from_manifest_file(
            path,
            jobs=jobs,
            step_timeout=step_timeout(args),
            run_check=not getattr(args, "no_check", False),
            use_remote=not getattr(args, "no_remote", False),
            executor_override=getattr(args, "executor", None),
            allow_outside=getattr(args, "allow_outside", False),
        )
    except ManifestError as error:
        raise error.relocate(path.resolve().parent, Path.cwd()) from None


DEFAULT_MANIFEST = "robot.yaml"
MANIFEST_SUFFIXES = (".yaml", ".yml")


def manifest_argument(
    parser: argparse.ArgumentParser, positional: bool = True, several: bool = False
) -> None:
    """Add the manifest the way every command takes it: an optional positional ``MANIFEST``
    (default robot.yaml; unless ``positional`` is False, for a command that sorts its
    positionals itself) and ``-m/--manifest``; with ``several``, any number of either.
    :func:`chosen_manifest` and :func:`chosen_manifests` read them."""
    if positional:
        parser.add_argument(
            "manifest",
            nargs="*" if several else "?",
            default=None,
            metavar="MANIFEST",
            help=f"the manifest{'s' if several else ''} (default: {DEFAULT_MANIFEST})",
        )
    parser.add_argument(
        "-m",
        "--manifest",
        dest="manifest_flag",
        action="append" if several else "store",
        default=None,
        metavar="MANIFEST",
        help="a manifest, as an option: the same as the positional argument"
        + (" (repeatable)" if several else ""),
    )


def chosen_manifest(args: argparse.Namespace, positional: str | None = None) -> str:
    """The manifest named by the positional argument or ``-m`` (not both), else robot.yaml."""
    from mjcfbuild.errors import UsageError

    given = positional if positional is not None else getattr(args, "manifest", None)
    flag = getattr(args, "manifest_flag", None)
    if given is not None and flag is not None and given != flag:
        raise UsageError(f"two manifests: '{given}' and -m '{flag}'", hint="name one, without -m")
    return given or flag or DEFAULT_MANIFEST


def chosen_manifests(args: argparse.Namespace) -> list[str]:
    """The manifests named as positional arguments and with ``-m``, in that order, else
    robot.yaml (a command given ``several=True`` by :func:`manifest_argument`)."""
    given = [
        *(getattr(args, "manifest", None) or []),
        *(getattr(args, "manifest_flag", None) or []),
    ]
    return list(dict.fromkeys(given)) or [DEFAULT_MANIFEST]


def looks_like_manifest(word: str) -> bool:
    """Whether a positional word is a manifest rather than something else (a task name): it
    ends in .yaml or .yml, or names an existing file."""
    return word.endswith(MANIFEST_SUFFIXES) or os.path.isfile(word)


def allow_outside_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--allow-outside``: the output folder may be outside the manifest's folder tree."""
    parser.add_argument(
        "--allow-outside",
        action="store_true",
        help="let output.folder be outside the folder of robot.yaml (as output.allow_outside: "
        "true does)",
    )
