"""What in an output folder is mjcfbuild's: the name of its state folder, and the files
there that are the user's, which no step may write over: those a build found there that no
build wrote, and outputs the user edited since a build wrote them that git does not hold.

A build lists those files (:func:`record_foreign`) when it takes the folder, and every step's
write (``steps.outputs.write_output``) asks :func:`refuse_foreign` first: a ``scene.xml``
or ``assets/base.obj`` the user put in the folder was replaced without a word, one that
``clean`` had kept as the user's was replaced once a mesh of that name came to the build, and
a model tuned by hand was replaced by the next build, the tuning lost.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from pathlib import Path
from typing import NamedTuple

STATE_DIR = ".mjcfbuild"
FOREIGN = "foreign.json"
# The state folder's .gitignore: it ignores itself in git.
STATE_IGNORE = b"# mjcfbuild's build state; not for version control\n*\n"


class Record(NamedTuple):
    """A folder's record of the user's files: every name, and those among them that are
    outputs a build wrote and the user edited since."""

    files: frozenset[str]
    edited: frozenset[str]


_NONE = Record(frozenset(), frozenset())

# The records each process read, by path: (what identifies that version of it, the record).
# A resident worker serves many builds; each writes its record anew (a new inode).
_read: dict[str, tuple[tuple[int, int, int], Record]] = {}


def record_foreign(out_dir: Path, names: Iterable[str], edited: Iterable[str] = ()) -> None:
    """Record ``names`` (relative to ``out_dir``, posix) as files no build wrote, and
    ``edited`` as outputs the user edited since a build wrote them; none removes the
    record."""
    from mjcfbuild.fsutil import write_if_changed

    path = out_dir / STATE_DIR / FOREIGN
    changed = sorted(set(edited))
    listed = sorted(set(names) | set(changed))
    if not listed:
        path.unlink(missing_ok=True)
        return
    record: dict[str, list[str]] = {"files": listed}
    if changed:
        record["edited"] = changed
    write_if_changed(path, (json.dumps(record, indent=1) + "\n").encode())
    write_if_changed(path.with_name(".gitignore"), STATE_IGNORE)  # clean left none


def refuse_foreign(path: Path, data: bytes) -> None:
    """Raise :class:`~mjcfbuild.errors.OutputError` when ``path`` is a file the build found
    in its output folder, that no build wrote, and ``data`` would change it."""
    for folder in list(path.parents)[:4]:  # the output folder: at most assets/x/ above it
        record = folder / STATE_DIR / FOREIGN
        if not (folder / STATE_DIR).is_dir():
            continue
        name = Path(os.path.relpath(path, folder)).as_posix()
        users = _record(record)
        if name not in users.files or not os.path.lexists(path) or _holds(path, data):
            return
        from mjcfbuild.errors import OutputError

        if name in users.edited:
            raise OutputError(
                "was edited since a build wrote it, and git has no commit of the edit; a build "
                "never writes over an edit of yours",
                file=str(path),
                hint=_settle(name, path),
            )
        raise OutputError(
            "is not mjcfbuild's (it was in the output folder before the build, and no build "
            "wrote it); a build never writes over a file of yours",
            file=str(path),
            hint="move it out of the folder (or remove it), or set output.folder to a folder "
            "of the build's own",
        )


def _settle(name: str, path: Path) -> str:
    """What to do about an output the user edited, ``name`` in its output folder."""
    if name.split("/", 1)[0] == "report":  # the build's own, which git ignores
        return "copy out what you need, then remove it (the report folder is the build's)"
    if path.suffix == ".xml":  # a model's tuning has a home in robot.yaml
        return (
            "carry the edit into robot.yaml's mujoco_inputs or actuators, which every build "
            "applies, then remove the file; or commit it first, and the build writes over it"
        )
    return (
        "copy out what you need, then remove it; or commit it first, and the build writes over it"
    )


def _record(record: Path) -> Record:
    try:
        stat = record.stat()
    except OSError:
        return _NONE
    version = (stat.st_ino, stat.st_size, stat.st_mtime_ns)
    cached = _read.get(str(record))
    if cached is not None and cached[0] == version:
        return cached[1]
    try:
        data = json.loads(record.read_text(encoding="utf-8"))
        files = frozenset(data["files"])
        read = Record(files, frozenset(data.get("edited", ())) & files)
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        read = _NONE
    _read[str(record)] = (version, read)
    return read


def _holds(path: Path, data: bytes) -> bool:
    try:
        return path.stat().st_size == len(data) and path.read_bytes() == data
    except OSError:
        return False  # gone, or a folder: writing it says what is wrong


def recorded_foreign(out_dir: Path) -> Record:
    """The folder's record of the user's files (empty without one)."""
    return _record(out_dir / STATE_DIR / FOREIGN)
