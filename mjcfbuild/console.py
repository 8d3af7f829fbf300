"""Errors and warnings as every front end prints them: ``mjcfbuild: error: ...`` and
``mjcfbuild: warning: ...`` on stderr, one line each.

The command line and the doit tasks of :mod:`mjcfbuild.engine.dodo` print through here, so a
build reads the same whichever started it.
"""

from __future__ import annotations

import sys
from pathlib import Path

from mjcfbuild.errors import InternalError, MjcfbuildError


def report_error(error: MjcfbuildError, debug: bool, base_dir: Path | None = None) -> None:
    """Print one error as ``mjcfbuild: error: file:line: message (hint)``."""
    if base_dir is not None:
        error.relocate(base_dir, Path.cwd())
    if _at_conflict_marker(error):
        error.hint = "git left a merge conflict's marker there: resolve the conflict, then build"
    text = error.one_line()
    if isinstance(error, InternalError) and not debug:
        text += " (an internal error: run again with --debug and report the output)"
    print(f"mjcfbuild: error: {text}", file=sys.stderr)
    if debug:
        details = error.traceback_text()
        if details:
            print(details.rstrip(), file=sys.stderr)


def _at_conflict_marker(error: MjcfbuildError) -> bool:
    """Whether ``error`` points at a line git's merge left (``<<<<<<<``, ``=======``,
    ``>>>>>>>``), or the line after one (where YAML's parser stops): a syntax error there is
    the conflict, not the file's syntax."""
    location = error.location
    if location is None or location.line is None:
        return False
    try:
        with open(location.file, "rb") as file:
            for number, line in enumerate(file, 1):
                if number >= location.line - 1 and _is_marker(line):
                    return True
                if number >= location.line:
                    return False
    except OSError:
        pass
    return False


def _is_marker(line: bytes) -> bool:
    """Whether ``line`` is one of git's conflict markers (``<<<<<<< ours``, ``=======``,
    ``>>>>>>> theirs``), not a banner of '=' signs in a comment."""
    return line[:8] in (b"<<<<<<< ", b">>>>>>> ") or line.rstrip() == b"======="


def report_warning(text: str) -> None:
    """Print one warning line."""
    print(f"mjcfbuild: warning: {text}", file=sys.stderr)


def report_warnings(
    warnings: list[str], listed_in: str = "", prefix: str = "", base_dir: Path | None = None
) -> None:
    """Print warnings one line per kind (:mod:`mjcfbuild.warning_groups`), each after
    ``prefix``; ``listed_in`` names the file that lists them all, for a kind with more
    subjects than a line shows. A warning that starts with a file of ``base_dir`` (the
    manifest's folder, as the report names it) names it from the current folder, as errors do."""
    from mjcfbuild.warning_groups import group_warnings

    if base_dir is not None:
        warnings = [_from_here(warning, base_dir) for warning in warnings]
    more = f"all in {listed_in}" if listed_in else ""
    for line in group_warnings(warnings, more):
        report_warning(prefix + line)


def shown_path(path: str | Path) -> str:
    """``path`` as the console names it: from the current folder, or absolute where that is
    shorter than climbing out of it."""
    import os

    relative = os.path.relpath(path)
    # normalised: a file beside the manifest's folder was named ".../robot/../../src/..."
    return os.path.normpath(path) if relative.startswith("..") else relative


def _from_here(warning: str, base_dir: Path) -> str:
    """``warning`` with its leading ``file:`` and the expanded URDF it names (``[expanded:
    file:line]``), both relative to ``base_dir``, named from here."""
    import re

    def here(name: str) -> str:
        file = base_dir / name
        return name if Path(name).is_absolute() or not file.exists() else shown_path(file)

    # A name may hold spaces (an output folder "my model"): only one that exists is renamed.
    warning = re.sub(r"\[expanded: ([^:\]]+)", lambda m: f"[expanded: {here(m.group(1))}", warning)
    found = re.match(r"([^:]+\.[A-Za-z0-9]+):", warning)
    if found is None:
        return warning
    return here(found.group(1)) + warning[found.end(1) :]
