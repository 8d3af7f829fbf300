"""What a build publishes for users to commit, and whether a build created or changed any of
it: ``mjcfbuild build --fail-on-change``, the pre-commit hook's way to fail as formatters do.

pre-commit itself notices a hook that modified a tracked file, but not one that created a file
(the first build in a description repo), and a file created and left untracked would pass the
next commit unnoticed. So the build compares what it publishes before and after, and asks git
which of those files it does not track (ignored ones, like the report's, do not count).
"""

from __future__ import annotations

import hashlib
import os
import subprocess
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext

Snapshot = dict[str, str]  # path -> MD5 of its bytes


def published_files(ctx: BuildContext) -> list[Path]:
    """The files a build of ``ctx`` publishes now: the model, the scene, the exported URDF,
    and what is under assets/, report/ and the URDF's mesh folder (not the state folder)."""
    from mjcfbuild.engine.stamp import files_under
    from mjcfbuild.outputs import report_dir

    files = [p for p in (ctx.robot_path, ctx.scene_path, ctx.urdf_path) if p and p.is_file()]
    for folder in (ctx.assets_dir, report_dir(ctx), ctx.urdf_mesh_dir):
        if folder is not None:
            files += files_under(folder)
    return sorted(set(files))


def snapshot(files: list[Path]) -> Snapshot:
    """The bytes (as MD5) of ``files``."""
    found: Snapshot = {}
    for path in files:
        digest = hashlib.md5(usedforsecurity=False)
        try:
            with open(path, "rb") as handle:
                while chunk := handle.read(1 << 20):
                    digest.update(chunk)
        except OSError:
            continue
        found[str(path)] = digest.hexdigest()
    return found


def changes(before: Snapshot, after: Snapshot) -> tuple[list[str], list[str]]:
    """(created, changed) files between two snapshots; removals leave a deletion for git
    to report itself."""
    created = sorted(name for name in after if name not in before)
    changed = sorted(name for name in after if name in before and before[name] != after[name])
    return created, changed


def git_status(files: list[str]) -> tuple[set[str], set[str]]:
    """(untracked, ignored): those of ``files`` that git neither tracks nor ignores, and those
    it ignores without tracking them. Both empty for files outside a git work tree."""
    by_folder: dict[str, list[str]] = {}
    for name in files:
        by_folder.setdefault(os.path.dirname(name), []).append(name)
    untracked: set[str] = set()
    ignored: set[str] = set()
    for folder, names in sorted(by_folder.items()):
        for found, extra in ((untracked, []), (ignored, ["--ignored"])):
            command = ["git", "ls-files", "--others", "--exclude-standard", *extra, "-z", "--"]
            try:
                done = subprocess.run([*command, *names], cwd=folder, capture_output=True)
            except OSError:
                return set(), set()  # no git
            if done.returncode != 0:
                break  # not a work tree
            listed = [entry for entry in done.stdout.decode().split("\0") if entry]
            found.update(os.path.normpath(os.path.join(folder, entry)) for entry in listed)
    return untracked, ignored


def unstaged(files: list[str]) -> set[str] | None:
    """Those of ``files`` whose bytes differ from what git's index holds for them (tracked
    files only); None outside a git work tree. A file a build rewrote to the bytes that are
    staged (a hand edit undone) needs no ``git add``."""
    by_folder: dict[str, list[str]] = {}
    for name in files:
        by_folder.setdefault(os.path.dirname(name), []).append(name)
    found: set[str] = set()
    for folder, names in sorted(by_folder.items()):
        command = ["git", "diff", "--name-only", "--relative", "-z", "--", *names]
        try:
            done = subprocess.run(command, cwd=folder, capture_output=True)
        except OSError:
            return None  # no git
        if done.returncode != 0:
            return None  # not a work tree
        listed = [entry for entry in done.stdout.decode().split("\0") if entry]
        found.update(os.path.normpath(os.path.join(folder, entry)) for entry in listed)
    return found


def git_holds(files: list[str]) -> set[str]:
    """Those of ``files`` git holds as they are: tracked, with the bytes its index has (staged
    or committed), or in a merge conflict (which a rebuild is how to resolve). Writing over one
    of them loses nothing. Empty outside a git work tree or without git."""
    by_folder: dict[str, list[str]] = {}
    for name in files:
        by_folder.setdefault(os.path.dirname(name), []).append(name)
    tracked: set[str] = set()
    conflicted: set[str] = set()
    for folder, names in sorted(by_folder.items()):
        command = ["git", "ls-files", "--stage", "-z", "--", *names]
        try:
            done = subprocess.run(command, cwd=folder, capture_output=True)
        except OSError:
            return set()  # no git
        if done.returncode != 0:
            continue  # not a work tree
        for entry in done.stdout.decode().split("\0"):
            info, tab, path = entry.partition("\t")
            if not tab:
                continue
            full = os.path.normpath(os.path.join(folder, path))
            (conflicted if info.split()[-1] != "0" else tracked).add(full)
    if not tracked:
        return conflicted
    differ = unstaged(sorted(tracked)) or set()
    return (tracked - differ) | conflicted


def in_work_tree(folder: str) -> bool:
    """Whether ``folder`` is in a git work tree (False without git)."""
    try:
        done = subprocess.run(
            ["git", "rev-parse", "--is-inside-work-tree"], cwd=folder, capture_output=True
        )
    except OSError:
        return False
    return done.returncode == 0 and done.stdout.strip() == b"true"
