"""What in an output folder is mjcfbuild's: the name of its state folder, and the files a
build found there that no build wrote, which no step may write over.

A build lists those files (:func:`record_foreign`) when it takes the folder, and every step's
write (``steps.outputs.write_output``) asks :func:`refuse_foreign` first: a ``scene.xml``
or ``assets/base.obj`` the user put in the folder was replaced without a word, and one that
``clean`` had kept as the user's was replaced once a mesh of that name came to the build.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from pathlib import Path

STATE_DIR = ".mjcfbuild"
FOREIGN = "foreign.json"

# The records each process read, by path: (what identifies that version of it, its names).
# A resident worker serves many builds; each writes its record anew (a new inode).
_read: dict[str, tuple[tuple[int, int, int], frozenset[str]]] = {}


def record_foreign(out_dir: Path, names: Iterable[str]) -> None:
    """Record ``names`` (relative to ``out_dir``, posix) as files no build wrote; none
    removes the record."""
    from mjcfbuild.fsutil import write_if_changed

    path = out_dir / STATE_DIR / FOREIGN
    listed = sorted(set(names))
    if not listed:
        path.unlink(missing_ok=True)
        return
    write_if_changed(path, (json.dumps({"files": listed}, indent=1) + "\n").encode())


def refuse_foreign(path: Path, data: bytes) -> None:
    """Raise :class:`~mjcfbuild.errors.OutputError` when ``path`` is a file the build found
    in its output folder, that no build wrote, and ``data`` would change it."""
    for folder in list(path.parents)[:4]:  # the output folder: at most assets/x/ above it
        record = folder / STATE_DIR / FOREIGN
        if not (folder / STATE_DIR).is_dir():
            continue
        name = Path(os.path.relpath(path, folder)).as_posix()
        if name not in _names(record) or not os.path.lexists(path) or _holds(path, data):
            return
        from mjcfbuild.errors import OutputError

        raise OutputError(
            "is not mjcfbuild's (it was in the output folder before the build, and no build "
            "wrote it); a build never writes over a file of yours",
            file=str(path),
            hint="move it out of the folder (or remove it), or set output.folder to a folder "
            "of the build's own",
        )


def _names(record: Path) -> frozenset[str]:
    try:
        stat = record.stat()
    except OSError:
        return frozenset()
    version = (stat.st_ino, stat.st_size, stat.st_mtime_ns)
    cached = _read.get(str(record))
    if cached is not None and cached[0] == version:
        return cached[1]
    try:
        names = frozenset(json.loads(record.read_text(encoding="utf-8"))["files"])
    except (OSError, ValueError, KeyError, TypeError):
        names = frozenset()
    _read[str(record)] = (version, names)
    return names


def _holds(path: Path, data: bytes) -> bool:
    try:
        return path.stat().st_size == len(data) and path.read_bytes() == data
    except OSError:
        return False  # gone, or a folder: writing it says what is wrong


def recorded_foreign(out_dir: Path) -> frozenset[str]:
    """The names the folder's record lists as files no build wrote (none without one)."""
    return _names(out_dir / STATE_DIR / FOREIGN)
