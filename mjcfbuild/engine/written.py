"""The record of the files builds wrote into the output folder: what ``mjcfbuild clean`` may
remove, and nothing else.

Each build adds to ``.mjcfbuild/written.json`` the files it wrote (every task's targets, the
files its steps reported writing, the report), as paths relative to the output folder. The
record only grows: a file a later build stops writing is still one mjcfbuild wrote. A file the
user put in the folder, even in ``assets/`` or ``report/``, is never in it.
"""

from __future__ import annotations

import json
import os
import stat
from collections.abc import Iterable
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING

from mjcfbuild.fsutil import write_if_changed

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


def recorded(ctx: BuildContext) -> list[str] | None:
    """The recorded files (relative to the output folder, sorted); None without a record (a
    folder no build wrote, or one an mjcfbuild from before the record built)."""
    try:
        data = json.loads(ctx.state(WRITTEN).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or not isinstance(data.get("files"), list):
        return None
    # The record is a file in the folder: accept only names that stay below it.
    return sorted(
        name
        for name in data["files"]
        if isinstance(name, str) and _relative(ctx.out_dir, ctx.out_dir / name) == name
    )


def record(ctx: BuildContext, paths: Iterable[str | os.PathLike]) -> None:
    """Add ``paths`` (those in the output folder, outside its state folder) to the record."""
    names = set(recorded(ctx) or [])
    for path in paths:
        name = _relative(ctx.out_dir, path)
        if name is not None and name.split("/", 1)[0] != ctx.state_dir.name:
            names.add(name)
    text = json.dumps({"files": sorted(names)}, indent=1) + "\n"
    write_if_changed(ctx.state(WRITTEN), text.encode())


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
    and the folders left empty there; a file the user put there stays. The names removed."""
    prefix = _relative(ctx.out_dir, below)
    if prefix is None:
        return []
    removed = []
    for name in recorded(ctx) or []:
        if (name == prefix or name.startswith(prefix + "/")) and written_file(ctx.out_dir, name):
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
