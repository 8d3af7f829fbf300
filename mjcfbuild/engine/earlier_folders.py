"""The output folders robot.yaml named before its ``output.folder`` changed.

Changing ``output.folder`` left the old folder with the old model, scene and assets, looking
current: a launch file or a colleague went on loading a model no build kept in sync, and
nothing said so. Every folder a build writes records which robot.yaml owns it
(``.mjcfbuild/owner.json``, :mod:`mjcfbuild.engine.guard`), and where that robot.yaml put it.
Once a build has written the model anew in its folder, the folders in robot.yaml's folder tree
that record the same robot.yaml and their own place (not a copy or a move: a snapshot) but
are not its output folder any more lose the files builds wrote there that still hold the
bytes a build wrote (:mod:`mjcfbuild.engine.written`), their state, and the folders left
empty. A file the user put there or edited stays, and the build names it; the edited ones
stay recorded as the user's (``.mjcfbuild/foreign.json``, as ``clean`` leaves them), so a
build into that folder again stops at them.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.engine.guard import OWNER, named_by_manifest
from mjcfbuild.ownership import STATE_DIR

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext

# Folders visited looking for earlier output folders: a description repository has hundreds;
# a build inside a workspace of thousands stops looking rather than slow every build.
_MOST_FOLDERS = 5000
# Folders no output folder is in (they are not the user's description).
_SKIPPED = {"node_modules", "__pycache__"}


@dataclass
class Abandoned:
    """An earlier output folder of the manifest, and what its removal did."""

    folder: Path
    removed: list[Path] = field(default_factory=list)  # the build's files, removed
    kept: list[Path] = field(default_factory=list)  # the user's files (or edits), kept


def remove_earlier_folders(ctx: BuildContext) -> list[Abandoned]:
    """Empty each earlier output folder of ``ctx``'s robot.yaml of the files builds wrote there
    (see the module's docstring); what was removed and kept in each."""
    if not named_by_manifest(ctx):
        return []
    return [_empty(ctx, folder) for folder in earlier_folders(ctx)]


def earlier_folders(ctx: BuildContext) -> list[Path]:
    """The folders in robot.yaml's folder tree whose state says this robot.yaml built there,
    where robot.yaml put them (not a copy or a move of one), other than its output folder
    now. Folders are compared as files (device and inode), not by name: a name in another
    letter case is the same folder on macOS."""
    assert ctx.manifest_file is not None, "only output folders robot.yaml names"
    manifest = _identity(ctx.manifest_file)
    current = _identity(ctx.out_dir)
    found = []
    for visited, (folder, subfolders, _) in enumerate(os.walk(ctx.base_dir)):
        if visited == _MOST_FOLDERS:
            break
        subfolders[:] = sorted(
            name
            for name in subfolders
            if not name.startswith(".")
            and name not in _SKIPPED
            and not os.path.islink(os.path.join(folder, name))
        )
        here = _identity(folder)
        if here is None or here == current or not os.path.isfile(_owner_file(folder)):
            continue
        owner, placed = _owner(folder)
        if owner is None or _identity(owner) != manifest or placed is None:
            continue
        if _identity(os.path.join(os.path.dirname(owner), placed)) == here:
            found.append(Path(folder))
    return found


def _identity(path: str | os.PathLike) -> tuple[int, int] | None:
    """The file ``path`` is (device and inode), None where there is none."""
    try:
        status = os.stat(path)
    except OSError:
        return None
    return status.st_dev, status.st_ino


def _owner_file(folder: str) -> str:
    return os.path.join(folder, STATE_DIR, OWNER)


def _owner(folder: str) -> tuple[str | None, str | None]:
    """The robot.yaml that ``folder``'s state says owns it, and where that robot.yaml put its
    output folder (relative to the robot.yaml's folder; None in a record from before)."""
    try:
        with open(_owner_file(folder), encoding="utf-8") as file:
            record = json.load(file)
    except (OSError, ValueError):
        return None, None
    if not isinstance(record, dict) or not isinstance(record.get("manifest"), str):
        return None, None
    placed = record.get("folder")
    return os.path.join(folder, record["manifest"]), placed if isinstance(placed, str) else None


def _empty(ctx: BuildContext, folder: Path) -> Abandoned:
    """Remove from ``folder`` the files its record says a build wrote and that still hold
    those bytes, then its state and the folders left empty; what was removed and kept."""
    from mjcfbuild.engine.written import edited, recorded_in, written_file

    abandoned = Abandoned(folder)
    state = folder / STATE_DIR
    for name, digest in (recorded_in(folder, state) or {}).items():
        if not written_file(folder, name):
            continue
        try:
            if not edited(folder, name, digest):
                (folder / name).unlink()
                abandoned.removed.append(folder / name)
                continue
        except OSError:  # not ours to remove (another user's file): it stays, and is named
            pass
        abandoned.kept.append(folder / name)
    shutil.rmtree(state, ignore_errors=True)
    if abandoned.kept:
        # The edits stay the user's, as after clean: a build of this folder again must stop
        # at them, not take them for a fresh clone's outputs and write over them.
        from mjcfbuild.ownership import record_foreign

        with contextlib.suppress(OSError):
            state.mkdir(exist_ok=True)
            kept = [path.relative_to(folder).as_posix() for path in abandoned.kept]
            record_foreign(folder, (), kept)
    keep = {Path(os.path.realpath(path)) for path in (ctx.base_dir, ctx.out_dir)}
    for emptied in sorted({p.parent for p in abandoned.removed}, key=_depth, reverse=True):
        _remove_empty(emptied, folder, keep)
    _remove_empty(folder, folder.parent, keep)
    if folder.is_dir() and not _holds(folder, keep):
        # A folder of its own (not robot.yaml's, nor one holding the output folder now): what
        # is left in it is the user's.
        left = (
            path
            for path in folder.rglob("*")
            if not path.is_dir() and path.relative_to(folder).parts[0] != STATE_DIR
        )
        abandoned.kept = sorted({*abandoned.kept, *left})
    return abandoned


def _holds(folder: Path, paths: set[Path]) -> bool:
    """Whether ``folder`` is one of ``paths`` or above one of them (compared as files)."""
    mine = _identity(folder)
    return mine is not None and any(
        _identity(above) == mine for path in paths for above in (path, *path.parents)
    )


def _depth(path: Path) -> int:
    """How many folders deep ``path`` is: the deepest are emptied first."""
    return len(path.parts)


def _remove_empty(folder: Path, stop: Path, keep: set[Path]) -> None:
    """Remove ``folder`` and the folders above it, up to ``stop`` (not included), while they
    are empty; never one in ``keep`` or one above them."""
    while folder != stop and folder.is_dir() and not folder.is_symlink():
        if _holds(folder, keep) or any(folder.iterdir()):
            return
        try:
            folder.rmdir()
        except OSError:
            return
        folder = folder.parent
