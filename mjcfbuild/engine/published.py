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


class GitUnavailable(Exception):
    """git could not be asked about a file in a git work tree (not installed, or it refuses
    the repository: another user's, "dubious ownership"); the message says which."""


def git_holds(files: list[str]) -> set[str]:
    """Those of ``files`` git holds as they are: committed, with the bytes HEAD has, or in a
    merge conflict whose markers are still in the file (a rebuild is how to resolve it; a
    conflict resolved by hand is not held). Writing over one of them loses nothing. Not held:
    a staged edit (the commit hook would write over it and ask for the result to be added,
    leaving the edit only in the index), and a file git is told not to look at
    (``--assume-unchanged``, ``--skip-worktree``: a local change kept out of commits). Empty
    outside a git work tree and before the first commit; :class:`GitUnavailable` where git
    cannot be asked."""
    by_folder: dict[str, list[str]] = {}
    for name in files:
        by_folder.setdefault(os.path.dirname(name), []).append(name)
    held: set[str] = set()
    for folder, names in sorted(by_folder.items()):
        committed = _git_names(folder, ["ls-tree", "-z", "--name-only", "HEAD", "--", *names])
        if committed is None:
            continue  # not a work tree, or nothing committed yet
        differ = _git_names(
            folder, ["diff", "HEAD", "--name-only", "--relative", "-z", "--", *names]
        )
        unmerged = ["diff", "--name-only", "--relative", "--diff-filter=U", "-z", "--", *names]
        conflicted = _git_names(folder, unmerged)
        flagged = _git_names(folder, ["ls-files", "-v", "-z", "--", *names], tagged=True)
        if differ is None or conflicted is None or flagged is None:
            continue
        held |= (committed - differ - flagged) | {
            path for path in conflicted if has_conflict_markers(path)
        }
    return held


def git_modified(folder: str) -> set[str]:
    """The tracked files below ``folder`` whose bytes differ from HEAD's (empty outside a
    work tree, before a commit, or where git cannot be asked)."""
    try:
        return (
            _git_names(folder, ["diff", "HEAD", "--name-only", "--relative", "-z", "--", "."])
            or set()
        )
    except GitUnavailable:
        return set()


def has_conflict_markers(path: str) -> bool:
    """Whether ``path`` still holds the markers of a merge conflict."""
    try:
        with open(path, "rb") as file:
            lines = {line[:8] for line in file}
    except OSError:
        return False
    return {b"<<<<<<< ", b">>>>>>> "} <= lines


def _git_names(folder: str, arguments: list[str], tagged: bool = False) -> set[str] | None:
    """The paths a git command run in ``folder`` lists (NUL-separated, relative to it), made
    full; None where the command fails because there is no work tree or commit to ask.
    ``tagged``: ``ls-files -v`` output, of which only the files git does not look at (tags
    in lower case: assume-unchanged; ``S``: skip-worktree) are returned."""
    try:
        done = subprocess.run(["git", *arguments], cwd=folder, capture_output=True)
    except OSError:
        if _in_checkout(folder):
            raise GitUnavailable("git is not installed, so it cannot say what it holds") from None
        return None
    if done.returncode != 0:
        error = os.fsdecode(done.stderr).strip().splitlines()
        first = error[0] if error else f"exit code {done.returncode}"
        if _in_checkout(folder) and "not a git repository" not in first and "HEAD" not in first:
            raise GitUnavailable(f"git could not be asked ({first})")
        return None
    listed = [entry for entry in os.fsdecode(done.stdout).split("\0") if entry]
    if tagged:
        listed = [entry[2:] for entry in listed if entry[:1].islower() or entry[:1] == "S"]
    return {os.path.normpath(os.path.join(folder, entry)) for entry in listed}


def _in_checkout(folder: str) -> bool:
    """Whether ``folder`` or one above it holds a ``.git``."""
    path = Path(folder).absolute()
    return any((above / ".git").exists() for above in [path, *path.parents])


def git_removed(files: list[str]) -> set[str]:
    """The files git's index has, in the folders of ``files`` (what a build publishes), that
    the work tree no longer does: an asset the model stopped using, which the build removed;
    unless its removal is staged, the commit keeps it. Only files directly in those folders
    (where the output folder is the description's own, the user's files lie below it)."""
    folders = sorted({os.path.dirname(name) for name in files})
    found: set[str] = set()
    for folder in folders:
        try:
            listed = _git_names(folder, ["ls-files", "--deleted", "-z", "--", "."])
        except GitUnavailable:
            continue
        found |= {
            path for path in listed or () if os.path.dirname(path) == os.path.normpath(folder)
        }
    return found


def git_deleted(files: list[str]) -> set[str]:
    """Those of ``files`` (removed from the work tree, with their folders perhaps) that git's
    index still has."""
    by_folder: dict[str, list[str]] = {}
    for name in files:
        folder = os.path.dirname(os.path.abspath(name))
        while not os.path.isdir(folder) and os.path.dirname(folder) != folder:
            folder = os.path.dirname(folder)
        by_folder.setdefault(folder, []).append(os.path.relpath(name, folder))
    found: set[str] = set()
    for folder, names in sorted(by_folder.items()):
        try:
            listed = _git_names(folder, ["ls-files", "--deleted", "-z", "--", *names])
        except GitUnavailable:
            continue
        found |= listed or set()
    return found


def in_work_tree(folder: str) -> bool:
    """Whether ``folder`` is in a git work tree (False without git)."""
    try:
        done = subprocess.run(
            ["git", "rev-parse", "--is-inside-work-tree"], cwd=folder, capture_output=True
        )
    except OSError:
        return False
    return done.returncode == 0 and done.stdout.strip() == b"true"
