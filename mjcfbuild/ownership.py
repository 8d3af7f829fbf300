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
    """A folder's record of the user's files: every name, those among them that are outputs
    a build wrote and the user edited since, and why git could not be asked about them."""

    files: frozenset[str]
    edited: frozenset[str]
    git_problem: str = ""


_NONE = Record(frozenset(), frozenset())

# The records each process read, by path: (what identifies that version of it, the record).
# A resident worker serves many builds; each writes its record anew (a new inode).
_read: dict[str, tuple[tuple[int, int, int], Record]] = {}


def record_foreign(
    out_dir: Path, names: Iterable[str], edited: Iterable[str] = (), git_problem: str = ""
) -> None:
    """Record ``names`` (relative to ``out_dir``, posix) as files no build wrote, and
    ``edited`` as outputs the user edited since a build wrote them (``git_problem``: why git
    could not say whether it has those edits); none removes the record."""
    from mjcfbuild.fsutil import write_if_changed

    path = out_dir / STATE_DIR / FOREIGN
    changed = sorted(set(edited))
    listed = sorted(set(names) | set(changed))
    if not listed:
        path.unlink(missing_ok=True)
        return
    record: dict[str, list[str] | str] = {"files": listed}
    if changed:
        record["edited"] = changed
    if git_problem:
        record["git_problem"] = git_problem
    write_if_changed(path, (json.dumps(record, indent=1) + "\n").encode())
    write_if_changed(path.with_name(".gitignore"), STATE_IGNORE)  # clean left none


JOURNAL = "wrote.log"  # every output a step wrote, as written: "<md5> <name>" a line


def _output_folder(path: Path) -> Path | None:
    """The output folder ``path`` lies in: the nearest folder above it (at most three up:
    assets/x/) that holds a state folder."""
    for folder in list(path.parents)[:4]:
        if (folder / STATE_DIR).is_dir():
            return folder
    return None


def note_written(path: Path, digest: str) -> None:
    """Journal that a step wrote ``path`` with the bytes of MD5 ``digest``, before anything
    else can fail: a step that writes some outputs and then fails (or a build killed before
    it records what it wrote) left new bytes under an old record's hash, which the next build
    took for the user's edit. :func:`journaled` reads the journal back."""
    folder = _output_folder(path)
    if folder is None:
        return
    name = Path(os.path.relpath(path, folder)).as_posix()
    if name.split("/", 1)[0] == STATE_DIR:
        return  # the build's state, never the user's
    # One short line, appended: whole even when two workers write at once.
    with open(folder / STATE_DIR / JOURNAL, "a", encoding="utf-8") as journal:
        journal.write(f"{digest} {name}\n")


def journaled(out_dir: Path) -> dict[str, set[str]]:
    """The journal of what steps wrote (:func:`note_written`): each name with the MD5s of the
    bytes written to it."""
    found: dict[str, set[str]] = {}
    try:
        text = (out_dir / STATE_DIR / JOURNAL).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return found
    for line in text.splitlines():
        digest, _, name = line.partition(" ")
        if name:
            found.setdefault(name, set()).add(digest)
    return found


def remove_output(path: Path) -> None:
    """Remove ``path``, an output a step wrote earlier and no longer writes, unless it is
    one of the user's (found there, or edited since: :func:`refuse_foreign`'s files)."""
    folder = _output_folder(path)
    if folder is not None:
        name = Path(os.path.relpath(path, folder)).as_posix()
        if name in _record(folder / STATE_DIR / FOREIGN).files:
            return
    path.unlink(missing_ok=True)


def refuse_foreign(path: Path, data: bytes) -> None:
    """Raise :class:`~mjcfbuild.errors.OutputError` when ``path`` is a file the build found
    in its output folder, that no build wrote, and ``data`` would change it."""
    folder = _output_folder(path)
    if folder is not None:
        record = folder / STATE_DIR / FOREIGN
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
                hint=_settle(name, path, users.git_problem),
            )
        raise OutputError(
            "is not mjcfbuild's (it was in the output folder before the build, and no build "
            "wrote it); a build never writes over a file of yours",
            file=str(path),
            hint="move it out of the folder (or remove it), or set output.folder to a folder "
            "of the build's own",
        )


def _settle(name: str, path: Path, git_problem: str) -> str:
    """What to do about an output the user edited, ``name`` in its output folder."""
    if name.split("/", 1)[0] == "report":  # the build's own, which git ignores
        return "copy out what you need, then remove it (the report folder is the build's)"
    if path.suffix == ".xml":  # a model's tuning has a home in robot.yaml
        keep = (
            "carry the edit into robot.yaml's mujoco_inputs or actuators, which every build "
            "applies, then remove the file"
        )
    else:
        keep = "copy out what you need, then remove it"
    if git_problem:  # git may well have it: only the user can tell
        return f"{keep}; {git_problem}: if it is committed, remove it"
    return f"{keep}; or commit it (past the commit hook: --no-verify), and the build writes over it"


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
        problem = data.get("git_problem", "")
        edited = frozenset(data.get("edited", ())) & files
        read = Record(files, edited, problem if isinstance(problem, str) else "")
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
