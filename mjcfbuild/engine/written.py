"""The record of the files builds wrote into the output folder: what ``mjcfbuild clean`` may
remove, and nothing else.

Each build records in ``.mjcfbuild/written.json`` the files it wrote (every task's targets, the
files its steps reported writing, the report), as paths relative to the output folder, each
with the MD5 of the bytes it wrote. ``clean`` removes a file only while it still holds those
bytes: one the user edited since is kept, and said so. A file the user put in the folder, even
in ``assets/`` or ``report/``, is never in the record. An entry stays while its file is there
(a file a later build stops writing but leaves is still mjcfbuild's); entries of files that
are gone are dropped. A record from an mjcfbuild before the hashes lists names alone: those
files are taken as unedited.
"""

from __future__ import annotations

import json
import os
import stat
from collections.abc import Iterable
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING

from mjcfbuild.fsutil import md5_file, write_if_changed

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext

WRITTEN = "written.json"


def _relative(out_dir: Path, path: str | os.PathLike) -> str | None:
    """``path`` relative to ``out_dir`` (posix), or None when it is not below it."""
    relative = os.path.relpath(os.path.normpath(os.path.abspath(path)), out_dir)
    parts = PurePosixPath(Path(relative).as_posix()).parts
    if not parts or parts[0] in (".", "..") or os.path.isabs(relative):
        return None
    return "/".join(parts)


def recorded(ctx: BuildContext) -> dict[str, str | None] | None:
    """The recorded files (relative to the output folder, sorted), each with the MD5 of what
    the build wrote (None in a record made before the hashes); None without a record (a folder
    no build wrote, or one an mjcfbuild from before the record built)."""
    return recorded_in(ctx.out_dir, ctx.state_dir)


def recorded_in(out_dir: Path, state_dir: Path) -> dict[str, str | None] | None:
    """:func:`recorded` of the output folder ``out_dir`` with its state in ``state_dir``."""
    try:
        data = json.loads((state_dir / WRITTEN).read_text())
    except (OSError, ValueError):
        return None
    files = data.get("files") if isinstance(data, dict) else None
    if isinstance(files, list):  # names alone: the record before the hashes
        files = dict.fromkeys(files)
    if not isinstance(files, dict):
        return None
    # The record is a file in the folder: accept only names that stay below it.
    kept = {
        name: digest if isinstance(digest, str) else None
        for name, digest in files.items()
        if isinstance(name, str) and _relative(out_dir, out_dir / name) == name
    }
    return dict(sorted(kept.items()))


def record(
    ctx: BuildContext, wrote: Iterable[str | os.PathLike], owned: Iterable[str | os.PathLike] = ()
) -> None:
    """Record the files in ``wrote`` (those in the output folder, outside its state folder) with
    the bytes they hold now, which the build wrote or found intact. ``owned`` are the build's
    files it did not vouch for (targets of tasks that failed or did not run): an earlier entry
    stays as it was, so a file the user edited is not taken for the build's; a file without
    one is recorded as it is, unless it is one of the user's (:mod:`mjcfbuild.ownership`).
    Entries of files that are gone are dropped."""
    from mjcfbuild.ownership import JOURNAL, recorded_foreign

    out = ctx.out_dir
    before = recorded(ctx) or {}
    entries = {name: digest for name, digest in before.items() if written_file(out, name)}
    users = recorded_foreign(out).files  # a build that stopped at one did not make it its own
    for settled in settled_by_journal(ctx):  # written by a step that failed after writing it
        entries[settled] = _digest(ctx, settled)
    for path in owned:
        name = _name(ctx, path)
        if name is None or name in entries or name in users:
            continue
        if written_file(out, name):
            entries[name] = _digest(ctx, name)
    for path in wrote:
        name = _name(ctx, path)
        if name is not None and written_file(out, name):
            entries[name] = _digest(ctx, name)
    text = json.dumps({"files": dict(sorted(entries.items()))}, indent=1) + "\n"
    write_if_changed(ctx.state(WRITTEN), text.encode())
    ctx.state(JOURNAL).unlink(missing_ok=True)  # all in the record now


def settled_by_journal(ctx: BuildContext) -> list[str]:
    """The files in the output folder whose bytes are ones a step journaled writing
    (:func:`mjcfbuild.ownership.note_written`): the build's, whatever the record says."""
    from mjcfbuild.ownership import journaled

    found = []
    for name, digests in sorted(journaled(ctx.out_dir).items()):
        inside = _name(ctx, ctx.out_dir / name) == name  # in the folder, not its state
        if inside and written_file(ctx.out_dir, name) and _digest(ctx, name) in digests:
            found.append(name)
    return found


def _name(ctx: BuildContext, path: str | os.PathLike) -> str | None:
    """The record's name of ``path``: None outside the output folder or in its state folder."""
    name = _relative(ctx.out_dir, path)
    if name is None or name.split("/", 1)[0] == ctx.state_dir.name:
        return None
    return name


def _digest(ctx: BuildContext, name: str) -> str | None:
    try:
        return ctx.session.hashes.md5(ctx.out_dir / name)
    except OSError:
        return None


def edited(out_dir: Path, name: str, digest: str | None) -> bool:
    """Whether the file ``name`` no longer holds the bytes recorded as written (``digest``);
    a record without a hash, or a file that cannot be read, counts as unedited."""
    if digest is None:
        return False
    try:
        return md5_file(out_dir / name) != digest
    except OSError:
        return False


def written_file(out_dir: Path, name: str) -> bool:
    """Whether ``out_dir/name`` is a regular file reached without passing a symbolic link: one
    that removing cannot delete anything outside the folder (a link itself is the user's)."""
    path = out_dir
    parts = name.split("/")
    for part in parts[:-1]:
        path = path / part
        if path.is_symlink() or not path.is_dir():
            return False
    try:
        return stat.S_ISREG((path / parts[-1]).lstat().st_mode)
    except OSError:
        return False


def remove_written(ctx: BuildContext, below: Path) -> list[str]:
    """Remove the files builds recorded writing under ``below`` (a folder in the output folder)
    and the folders left empty there; a file the user put or edited there stays. The names
    removed."""
    prefix = _relative(ctx.out_dir, below)
    if prefix is None:
        return []
    removed = []
    for name, digest in (recorded(ctx) or {}).items():
        if not (name == prefix or name.startswith(prefix + "/")):
            continue
        if written_file(ctx.out_dir, name) and not edited(ctx.out_dir, name, digest):
            (ctx.out_dir / name).unlink()
            removed.append(name)
    if below.is_dir() and not below.is_symlink():
        folders = sorted(
            (p for p in below.rglob("*") if p.is_dir() and not p.is_symlink()), reverse=True
        )
        for folder in [*folders, below]:
            if not any(folder.iterdir()):
                folder.rmdir()
    return removed
