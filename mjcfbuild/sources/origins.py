"""Where the elements of an expanded URDF were written: errors about them point there.

The ``expand`` step of a xacro source writes, beside the expanded URDF, the file and line
where each line's element was written (through includes and macros: the line of the element
inside the macro's body). An error that points at a line of the expanded URDF is moved to
that place, and keeps the expanded line as a second reference.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path

from mjcfbuild.errors import MjcfbuildError, first_at


def origins_file(urdf: Path) -> Path:
    """The origins of the expanded URDF ``urdf``."""
    return urdf.with_name(urdf.name.removesuffix(".urdf") + ".origins.json")


def origins_json(origins: dict[int, tuple[str, int]]) -> bytes:
    """``origins`` (line -> file, line) as the bytes of the origins file; an empty map for a
    plain URDF. The step that expanded the URDF writes them beside it."""
    data = {str(line): [file, written] for line, (file, written) in sorted(origins.items())}
    return (json.dumps(data, sort_keys=True, separators=(",", ":")) + "\n").encode()


def written_at(urdf: Path, line: int) -> tuple[str, int] | None:
    """Where the element at (or, inside it, before) ``line`` of ``urdf`` was written."""
    return written_in(read_origins(urdf), line)


def read_origins(urdf: Path) -> dict[int, tuple[str, int]]:
    """The origins file of the expanded URDF ``urdf`` (empty where it has none)."""
    try:
        data = json.loads(origins_file(urdf).read_text())
    except (OSError, ValueError):
        return {}
    if not isinstance(data, dict):
        return {}
    return {int(key): (str(f), int(n)) for key, (f, n) in data.items() if key.isdigit()}


def written_in(origins: dict[int, tuple[str, int]], line: int) -> tuple[str, int] | None:
    """Where ``origins`` (an expansion's, in memory) say the element at (or, inside it,
    before) an expanded ``line`` was written; None for a URDF read as written."""
    before = [number for number in origins if number <= line]
    return origins[max(before)] if before else None


def map_lines(
    error: MjcfbuildError,
    origins: dict[int, tuple[str, int]],
    shown: Callable[[str], str] = str,
) -> int | None:
    """Point ``error``, at an expanded URDF's line, where ``origins`` say that element was
    written (its file as ``shown`` names it), and its second line (``first at line N``) too:
    the one mapping of an error's lines, for build, init and check. Returns the expanded line
    it pointed at; None where it points at no line ``origins`` know (a URDF read as written)."""
    location = error.location
    if location is None or location.line is None:
        return None
    found = written_in(origins, location.line)
    if found is None:
        return None
    expanded = location.line
    location.file, location.line, location.column = shown(found[0]), found[1], None
    if error.first_line is not None:
        old = first_at(error.first_line)
        first = written_in(origins, error.first_line)
        if first is not None and old in error.message:
            other = shown(first[0])
            new = first_at(first[1], None if other == location.file else other)
            error.message = error.message.replace(old, new, 1)
            error.first_line = None  # mapped: said once
    return expanded


def point_at_source(
    error: MjcfbuildError,
    urdf: Path,
    label: str,
    base_dir: Path,
    xacro: Path | None = None,
    expanded_from: Path | None = None,
) -> None:
    """If ``error`` points at a line of the expanded URDF ``urdf`` (shown as ``label``,
    relative to ``base_dir``), point it where that element was written, and name the
    expanded line in its message (from ``expanded_from``, else the current folder). An error
    about the whole expanded URDF (no line) points at ``xacro``, the file it was expanded
    from, where one is given: the user never wrote the expanded file."""
    location = error.location
    if location is None or location.file != label:
        return
    expanded = _expanded_name(urdf, expanded_from)
    if location.line is None:
        if xacro is not None:
            error.message += f" [expanded: {expanded}]"
            location.file = _shown(str(xacro), base_dir)
        return
    expanded_line = map_lines(error, read_origins(urdf), lambda file: _shown(file, base_dir))
    if expanded_line is None:
        return
    error.message += f" [expanded: {expanded}:{expanded_line}]"
    if error.hint and error.hint.startswith("the line is in the expansion of"):
        error.hint = None


def point_warning_at_source(text: str, urdf: Path, label: str, base_dir: Path) -> str:
    """A warning that starts ``label:line:`` (a line of the expanded URDF ``urdf``), started
    instead with where that element was written (:func:`source_location`), the expanded line
    named after it; others unchanged."""
    head = f"{label}:"
    if not text.startswith(head):
        return text
    number, sep, rest = text[len(head) :].partition(":")
    if not sep or not number.isdigit():
        return text
    expanded = f"{label}:{number}"
    where = source_location(expanded, urdf, label, base_dir)
    if where == expanded:
        return text
    # Named from base_dir even outside it, as the source is: the report stays the same bytes
    # wherever the output folder is (the console names it from the current folder).
    expanded_name = Path(os.path.relpath(urdf, base_dir)).as_posix()
    return f"{where}: {rest.strip()} [expanded: {expanded_name}:{number}]"


def source_location(where: str, urdf: Path, label: str, base_dir: Path) -> str:
    """``where``, a ``label:line`` of the expanded URDF ``urdf``, as the ``file:line`` where
    that line's element was written; any other ``where`` (another file, no line, a URDF read
    as written) as it is. The file is named from ``base_dir`` even outside it (``../x.xacro``):
    the report keeps it, whichever folder the build ran in, and the console names it from
    the current folder (console.report_warnings)."""
    number = where.removeprefix(f"{label}:")
    if number == where or not number.isdigit():
        return where
    found = written_in(read_origins(urdf), int(number))
    if found is None:
        return where
    return f"{Path(os.path.relpath(found[0], base_dir)).as_posix()}:{found[1]}"


def _expanded_name(urdf: Path, expanded_from: Path | None) -> str:
    """The expanded URDF as an error names it: from ``expanded_from`` (else the current
    folder), or absolute where that would climb out of it."""
    expanded = os.path.relpath(urdf, expanded_from)
    return str(urdf) if expanded.startswith("..") else expanded


def _shown(file: str, base_dir: Path) -> str:
    """``file`` relative to ``base_dir`` where it is inside it."""
    try:
        return str(Path(file).relative_to(base_dir))
    except ValueError:
        return file
