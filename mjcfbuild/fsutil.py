"""File-system helpers: one spelling per path, and writes that are never seen half-done."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from mjcfbuild.failpoints import failpoint

TEMP_SUFFIX = ".mjcfbuild-tmp"


def normalise(path: str | os.PathLike) -> Path:
    """An absolute path without '.' or '..' parts (symlinks kept), so a file has one name."""
    return Path(os.path.normpath(os.path.abspath(path)))


def unreadable_file(path: str | os.PathLike) -> str | None:
    """Why ``path`` is not a readable file, as words that follow its name ("not found", "is a
    folder, not a file", ...); None when it is one."""
    import errno
    import stat

    try:
        mode = os.stat(path).st_mode
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            return "is a symbolic link loop"
        if exc.errno in (errno.ENOENT, errno.ENOTDIR):
            if os.path.islink(path):
                return "is a broken symbolic link"
            match = case_match(path)
            if match is not None:
                return f"not found; did you mean '{case_suggestion(path, match)}'?"
            return "not found"
        return f"is not readable ({exc.strerror})"
    if stat.S_ISDIR(mode):
        return "is a folder, not a file"
    if not stat.S_ISREG(mode):
        return "is not a regular file"
    if not os.access(path, os.R_OK):
        return "is not readable (permission denied)"
    return None


def case_match(path: str | os.PathLike) -> Path | None:
    """The existing file or folder whose name differs from missing ``path`` only in letter
    case (``part.STL`` for ``part.stl``, ``Meshes/`` for ``meshes/``), or None.

    Each missing part of the path is matched against its folder's entries ignoring case; where
    several match, the first in sorted order is taken."""
    absolute = normalise(path)
    found = Path(absolute.anchor)
    changed = False
    for part in absolute.parts[1:]:
        if os.path.lexists(found / part):
            found = found / part
            continue
        try:
            entries = sorted(os.listdir(found))
        except OSError:
            return None
        same = [entry for entry in entries if entry.casefold() == part.casefold()]
        if not same:
            return None
        found, changed = found / same[0], True
    return found if changed and os.path.exists(found) else None


def case_suggestion(path: str | os.PathLike, match: Path) -> str:
    """How to write ``path`` as ``match`` (from :func:`case_match`) is spelt: ``path`` with
    the name of each part that differs replaced, from the first of them on."""
    asked = normalise(path).parts
    first = next(i for i, (a, b) in enumerate(zip(asked, match.parts, strict=True)) if a != b)
    return "/".join(match.parts[first:])


def atomic_write(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file and a rename.

    A reader (or a later build after a crash) sees either the old file or the new one, never a
    partial write. The temporary file carries :data:`TEMP_SUFFIX` so leftovers of a killed
    build can be recognised and removed.
    """
    path = Path(path)
    temp = path.with_name(f".{path.name}.{os.getpid()}{TEMP_SUFFIX}")
    try:
        with open(temp, "wb") as handle:
            handle.write(data[: len(data) // 2])
            failpoint(f"write:{path.name}")  # half a file on disk: what a crash here leaves
            handle.write(data[len(data) // 2 :])
        os.replace(temp, path)
    except BaseException as exc:
        temp.unlink(missing_ok=True)
        if isinstance(exc, OSError) and exc.filename in (None, str(temp)):
            # A failed write() names no file, and the temporary name means nothing to a user.
            exc.filename = str(path)
        raise


def write_if_changed(path: str | os.PathLike, data: bytes) -> bool:
    """Atomically write ``data`` unless ``path`` already holds exactly it; True if written."""
    path = Path(path)
    try:
        if path.stat().st_size == len(data) and path.read_bytes() == data:
            return False
    except OSError:
        pass
    atomic_write(path, data)
    return True


def md5_file(path: str | os.PathLike) -> str:
    """Hex MD5 of a file's bytes, read in blocks."""
    digest = hashlib.md5(usedforsecurity=False)
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def remove_stale_temp_files(folder: Path) -> None:
    """Delete temporary files a killed build left in ``folder`` (not recursive)."""
    try:
        entries = list(folder.iterdir())
    except OSError:
        return
    for entry in entries:
        if entry.name.endswith(TEMP_SUFFIX):
            entry.unlink(missing_ok=True)
