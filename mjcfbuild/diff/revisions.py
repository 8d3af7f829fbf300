"""Git revisions of a description repo, each built in a scratch folder of its own.

A revision's files come from ``git archive`` (the repo's checkout, index and worktree list are
left alone); they go to ``<scratch>/<side>/src`` and its build to ``<scratch>/<side>/out``.
The output folder stays between runs, so a revision is built incrementally from the last one
on the same side, and what both sides share (mesh products, decompositions, collision
matrices) comes from the shared cache. A new revision's files keep the size and time of the
last one's when two commits were made in the same second (``git archive`` gives every file its
commit's time in whole seconds), often their inodes too; their status-change time is new, and
the build trusts no file whose signature changed (:mod:`mjcfbuild.filesig`), so the folder
built for one revision is never taken as current for another.
"""

from __future__ import annotations

import hashlib
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

from mjcfbuild.errors import InputError, UsageError


@dataclass(frozen=True)
class Repository:
    """A git work tree and where the manifest lies in it."""

    top: Path
    manifest: Path  # relative to top

    @property
    def key(self) -> str:
        """A short name for the repo's scratch folders, from where it is on disk."""
        return hashlib.sha256(str(self.top).encode()).hexdigest()[:12]


@dataclass(frozen=True)
class Revision:
    """A commit resolved from what the user wrote."""

    ref: str
    commit: str

    @property
    def label(self) -> str:
        """``main (0123abc)``, or the short commit alone when that is what was written."""
        short = self.commit[:10]
        return short if self.commit.startswith(self.ref) else f"{self.ref} ({short})"


def _git(top: Path, *args: str, binary: bool = False) -> subprocess.CompletedProcess:
    try:
        return subprocess.run(
            ["git", "-C", str(top), *args], capture_output=True, text=not binary, check=False
        )
    except FileNotFoundError:
        raise InputError("git is not installed", hint="install git, or give --folders") from None


def repository(manifest: Path) -> Repository:
    """The git work tree that holds ``manifest``; :class:`InputError` outside one."""
    folder = manifest.resolve().parent
    if not manifest.is_file():
        raise InputError("no such manifest", file=str(manifest), hint="give the robot.yaml to diff")
    result = _git(folder, "rev-parse", "--show-toplevel")
    if result.returncode != 0:
        raise InputError(
            "not inside a git repository",
            file=str(manifest),
            hint="diff --base needs the description repo's history; or give --folders OLD NEW",
        )
    top = Path(result.stdout.strip()).resolve()
    return Repository(top, manifest.resolve().relative_to(top))


def resolve(repo: Repository, ref: str) -> Revision:
    """The commit ``ref`` names; :class:`UsageError` (exit 2) when it names none."""
    if ref.startswith("-"):
        raise UsageError(f"'{ref}' is not a git revision")
    result = _git(repo.top, "rev-parse", "--verify", "--quiet", f"{ref}^{{commit}}")
    if result.returncode != 0:
        raise UsageError(
            f"no git revision '{ref}' in {repo.top}",
            hint="give a branch, tag or commit that exists (git fetch it first in CI)",
        )
    return Revision(ref, result.stdout.strip())


def extract(repo: Repository, revision: Revision, side: Path) -> Path:
    """The revision's files under ``side/src`` (extracted again only when the commit changed);
    the manifest's path there."""
    import io
    import tarfile

    source = side / "src"
    stamp = side / "commit"
    manifest = source / repo.manifest
    if stamp.is_file() and stamp.read_text().strip() == revision.commit and source.is_dir():
        return _manifest_at(manifest, revision)
    if source.exists():
        shutil.rmtree(source)
    stamp.unlink(missing_ok=True)
    archive = _git(repo.top, "archive", "--format=tar", revision.commit, binary=True)
    if archive.returncode != 0:
        message = archive.stderr.decode(errors="replace").strip().splitlines()
        raise InputError(
            f"git archive {revision.label} failed: {message[0] if message else 'no output'}",
            file=str(repo.top),
        )
    source.mkdir(parents=True)
    with tarfile.open(fileobj=io.BytesIO(archive.stdout)) as tar:
        tar.extractall(source, filter="data")
    stamp.write_text(revision.commit + "\n")
    return _manifest_at(manifest, revision)


def _manifest_at(manifest: Path, revision: Revision) -> Path:
    if not manifest.is_file():
        raise InputError(
            f"the manifest does not exist at {revision.label}",
            file=str(manifest.name),
            hint="diff revisions that both have it",
        )
    return manifest
