"""The errors mjcfbuild reports to users, and the exit code each one maps to.

Every error a user can cause is a :class:`MjcfbuildError`: it carries a one-line message, the
file (and line, where there is one) it is about, and what to do about it. The command line
prints it as ``file:line: message (hint)`` and exits with the error's code; only ``--debug``
shows a traceback.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

EXIT_OK = 0
EXIT_BUILD_FAILED = 1
EXIT_USAGE = 2
EXIT_MANIFEST = 3
EXIT_INPUT = 4
EXIT_MODEL = 5
EXIT_CHECK = 6
EXIT_OUTPUT = 7
EXIT_INTERNAL = 70
EXIT_RESTART = 75  # sysexits' EX_TEMPFAIL: try again
EXIT_INTERRUPTED = 130  # 128 + SIGINT
EXIT_TERMINATED = 143  # 128 + SIGTERM

EXIT_CODES: dict[int, str] = {
    EXIT_OK: "success",
    EXIT_BUILD_FAILED: "a build step failed for a reason not listed below",
    EXIT_USAGE: "bad command line",
    EXIT_MANIFEST: "robot.yaml is invalid",
    EXIT_INPUT: "an input (URDF, xacro, mesh, package, inputs file) is missing or invalid",
    EXIT_MODEL: "MuJoCo rejected the assembled model",
    EXIT_CHECK: "a check failed, or outputs are out of date",
    EXIT_OUTPUT: "an output could not be written (a full disk, no permission), or another build "
    "held the output folder past --timeout",
    EXIT_INTERNAL: "internal error in mjcfbuild (please report it, with --debug output)",
    EXIT_RESTART: "watch ended: mjcfbuild or an installed package changed; start it again",
    EXIT_INTERRUPTED: "interrupted (Ctrl-C, SIGINT)",
    EXIT_TERMINATED: "interrupted by SIGTERM",
}


@dataclass
class Location:
    """Where an error points: a file and, when known, a line and column."""

    file: str
    line: int | None = None
    column: int | None = None

    def __str__(self) -> str:
        text = self.file
        if self.line is not None:
            text += f":{self.line}"
            if self.column is not None:
                text += f":{self.column}"
        return text


class MjcfbuildError(Exception):
    """Base class of every error mjcfbuild reports to a user."""

    exit_code = EXIT_BUILD_FAILED

    def __init__(
        self,
        message: str,
        *,
        file: str | Path | None = None,
        line: int | None = None,
        column: int | None = None,
        hint: str | None = None,
        first_line: int | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.location = Location(str(file), line, column) if file is not None else None
        self.hint = hint
        # A second line of the same file the message names as " (first at line N)" (a name
        # defined twice): moved with the location where an expanded URDF's lines are mapped
        # back to the xacro files that wrote them (sources.origins.map_lines).
        self.first_line = first_line
        # The traceback where the error was raised in another process (a worker), for --debug.
        self.details = ""

    def one_line(self) -> str:
        """The error as the single line the command line prints."""
        text = self.message
        if self.location is not None:
            text = f"{self.location}: {text}"
        if self.hint:
            text = f"{text} ({self.hint})"
        return " ".join(text.split())

    def relocate(self, base_dir: Path, cwd: Path) -> MjcfbuildError:
        """Show the file (relative to ``base_dir``, or absolute) relative to ``cwd`` when it is
        inside ``cwd``, and as an absolute path otherwise."""
        import os

        if self.location is not None:
            absolute = os.path.normpath(os.path.join(base_dir, self.location.file))
            relative = os.path.relpath(absolute, cwd)
            self.location.file = absolute if relative.startswith("..") else relative
        return self

    def to_dict(self) -> dict:
        """A JSON-friendly form, used to send errors from worker processes."""
        loc = self.location
        return {
            "type": type(self).__name__,
            "message": self.message,
            "file": loc.file if loc else None,
            "line": loc.line if loc else None,
            "column": loc.column if loc else None,
            "hint": self.hint,
            "first_line": self.first_line,
            "details": self.details or _traceback_of(self),
        }

    @staticmethod
    def from_dict(data: dict) -> MjcfbuildError:
        """Rebuild an error sent by :meth:`to_dict`, keeping its class."""
        cls = _ERROR_CLASSES.get(data.get("type", ""), MjcfbuildError)
        error = cls(
            data["message"],
            file=data.get("file"),
            line=data.get("line"),
            column=data.get("column"),
            hint=data.get("hint"),
            first_line=data.get("first_line"),
        )
        error.details = data.get("details") or ""
        return error

    def traceback_text(self) -> str:
        """The traceback to show with ``--debug``: where the error was raised (in a worker
        process, or in this one), or empty when it was made without being raised."""
        return self.details or _traceback_of(self)


def first_at(line: int | None, file: str | None = None) -> str:
    """`` (first at line N)`` in an error about a name given twice (``file:N`` where the first
    is in another file than the one the error points at)."""
    if not line:
        return ""
    return f" (first at {file}:{line})" if file else f" (first at line {line})"


def _traceback_of(error: BaseException) -> str:
    if error.__traceback__ is None:
        return ""
    import traceback

    return "".join(traceback.format_exception(error))


class UsageError(MjcfbuildError):
    """The command line is wrong."""

    exit_code = EXIT_USAGE


class ManifestError(MjcfbuildError):
    """robot.yaml cannot be read or does not validate."""

    exit_code = EXIT_MANIFEST


class InputError(MjcfbuildError):
    """A source file, package, mesh or inputs file is missing or malformed."""

    exit_code = EXIT_INPUT


class ModelError(MjcfbuildError):
    """MuJoCo refused the model mjcfbuild assembled."""

    exit_code = EXIT_MODEL


class CheckError(MjcfbuildError):
    """A check of the built model against its source failed."""

    exit_code = EXIT_CHECK


class OutputError(MjcfbuildError):
    """An output cannot be written."""

    exit_code = EXIT_OUTPUT


# Why a file could not be written, in words, and what to do, by errno.
_WRITE_FAILURES: dict[str, tuple[str, str]] = {
    "ENOSPC": ("no space left on the device", "free some space there, or build on another disk"),
    "EDQUOT": ("disk quota exceeded", "free some space there, or build on another disk"),
    "EFBIG": ("file too large for its file system", "build on another disk"),
    "EROFS": ("read-only file system", "build in a folder that can be written"),
    "EACCES": ("permission denied", "check the permissions of the file and its folder"),
    "EPERM": ("permission denied", "check the permissions of the file and its folder"),
    "ENAMETOOLONG": (
        "file name too long for its file system",
        "shorten the name robot.yaml gives it (name:, output:)",
    ),
}


def write_failure(exc: BaseException, file: str | Path | None = None) -> MjcfbuildError | None:
    """The one-line error of an :class:`OSError` that says a file could not be written (no
    space left, quota, permission denied, read-only), naming ``file`` (else the error's own
    file name): an :class:`OutputError`, or an :class:`InputError` for permission to read a
    file that is there. None for any other exception."""
    import errno
    import os

    if not isinstance(exc, OSError) or exc.errno is None:
        return None
    code = errno.errorcode.get(exc.errno, "")
    if code not in _WRITE_FAILURES:
        return None
    words, hint = _WRITE_FAILURES[code]
    name = file if file is not None else exc.filename
    if name is None:
        return OutputError(f"cannot write a file: {words}", hint=hint)
    path = os.fsdecode(name) if isinstance(name, (str, bytes, os.PathLike)) else str(name)
    if code in ("EACCES", "EPERM") and os.path.isfile(path) and not os.access(path, os.R_OK):
        return InputError(f"cannot read: {words}", file=path, hint="check its permissions")
    return OutputError(f"cannot write: {words}", file=path, hint=hint)


class TaskCrashed(MjcfbuildError):
    """A build step's worker process died (a crash in C++ code) or ran out of time."""

    exit_code = EXIT_BUILD_FAILED


class InternalError(MjcfbuildError):
    """A bug in mjcfbuild; the message carries the original exception."""

    exit_code = EXIT_INTERNAL

    def __init__(self, message: str, *, details: str = "", **kwargs) -> None:
        super().__init__(message, **kwargs)
        self.details = details


class BuildFailed(MjcfbuildError):
    """Raised by :func:`mjcfbuild.build` when one or more build steps failed."""

    def __init__(self, errors: list[MjcfbuildError]) -> None:
        first = errors[0] if errors else MjcfbuildError("build failed")
        super().__init__(first.one_line())
        self.errors = errors
        self.exit_code = first.exit_code


_ERROR_CLASSES: dict[str, type[MjcfbuildError]] = {
    cls.__name__: cls
    for cls in (
        MjcfbuildError,
        UsageError,
        ManifestError,
        InputError,
        ModelError,
        CheckError,
        OutputError,
        TaskCrashed,
        InternalError,
    )
}
