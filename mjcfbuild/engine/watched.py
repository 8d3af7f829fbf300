"""What ``mjcfbuild watch`` watches between builds, and how it tells that something changed.

After a build that left a stamp (:mod:`mjcfbuild.engine.stamp`), the watched files are the ones
the stamp lists - every file the build read or wrote, and those it looked for and did not find
- each as the stamp recorded it. The stamp records an input as the build found it (no stamp is
written when an input changed while the build ran), so an edit made during a build is seen as
a change afterwards, and the build's own outputs as they were written. The folders Python
imports packages from are watched too.

Without a stamp (the build failed, or could not write one), what the build read is not fully
known: every file below the manifest's folder, its source's folder and its packages' folders
is watched (:data:`MOST_TREE_FILES` at most), and each of those folders by its names (a file
the failed build looked for, created later, is a change), with the last stamp's files, except
what a build writes - output folders (those holding a build's state folder; where that is
the manifest's folder itself, the files its builds recorded writing), the files the last
stamp lists as written, MuJoCo's log, the file the watch's own output goes to - each
compared with what it was before the build started, so that a fix saved while a failing
build still ran is not missed.

A file counts as changed when its signature (:mod:`mjcfbuild.filesig`) moves, as for the no-op
fast path; one recorded within the file system's tick of its last change is compared by its
bytes too, once that tick has passed.
"""

from __future__ import annotations

import hashlib
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from stat import S_ISREG

from mjcfbuild import filesig
from mjcfbuild.engine.written import WRITTEN
from mjcfbuild.graph.context import STATE_DIR  # a folder holding one is an output folder

# Never watched below the manifest's folder: version control, caches, environments.
SKIPPED = frozenset({".git", ".hg", ".svn", "__pycache__", "node_modules", ".venv"})
# What MuJoCo writes in the current folder (a build's workers run in the manifest's) on errors.
MUJOCO_LOG = "MUJOCO_LOG.TXT"
# At most this many files below the manifest's folder (a manifest at the top of a monorepo).
MOST_TREE_FILES = 20_000


@dataclass
class Record:
    """One file as last seen: its signature (None when absent), its MD5 where known, and
    whether that signature may still miss a change made in the same clock tick (``racy``:
    the MD5 decides once the tick has passed)."""

    signature: list[int] | None
    md5: str | None = None
    racy: bool = False
    listing: tuple[str, ...] | None = None  # a folder's (a path ending in os.sep): its names


@dataclass
class Watched:
    """Files and what they were; ``code``: those whose change means mjcfbuild itself or an
    installed package changed (the command must start again to use them)."""

    records: dict[str, Record] = field(default_factory=dict)
    code: frozenset[str] = frozenset()
    written: frozenset[str] = frozenset()  # those the build wrote (from its stamp)

    @classmethod
    def take(cls, paths: list[str], code: frozenset[str] = frozenset()) -> Watched:
        """``paths`` as they are now."""
        now = time.time_ns()
        return cls({path: record_now(path, now) for path in paths}, code)

    def changed(self) -> list[str]:
        """The files that changed since they were recorded (or appeared, or went), sorted;
        a record whose tick has passed with the same bytes is trusted from now on."""
        now = time.time_ns()
        found = []
        for path, before in self.records.items():
            stat = _stat(path)
            signature = None if stat is None else filesig.signature(stat)
            if before.listing is not None and signature != before.signature:
                # A folder: only files coming or going count (not a folder a build made).
                listing = _listing(path)
                if listing != before.listing:
                    found.append(path)
                else:
                    self.records[path] = record_now(path, now)
            elif signature != before.signature:
                found.append(path)
            elif before.racy and stat is not None and not filesig.racy(stat, now):
                if _md5(path) != before.md5 or _listing(path) != before.listing:
                    found.append(path)
                else:
                    self.records[path] = Record(signature, before.md5, listing=before.listing)
        return sorted(found)

    def edited(self, changed: list[str]) -> list[str]:
        """Those of ``changed`` whose bytes are not the recorded ones (where the MD5 was
        recorded; the others count as edited): what to name, rather than files only touched."""
        named = []
        for path in changed:
            record = self.records.get(path)
            if record is not None and path.endswith(os.sep):  # a folder: what came
                came = sorted(set(_listing(path) or ()) - set(record.listing or ()))
                named += [os.path.join(path, name) for name in came]
            elif record is None or record.md5 is None or _md5(path) != record.md5:
                named.append(path)
        return named

    def again(self) -> Watched:
        """The same files, as they are now."""
        return Watched.take(list(self.records), self.code)


def from_stamp(manifest: Path, run_check: bool) -> Watched | None:
    """The files the stamp of the last successful build of ``manifest`` lists, as it recorded
    them, and the package folders as they are now; None without a stamp."""
    from mjcfbuild.engine import stamp

    found = stamp.recorded(manifest, run_check)
    if found is None:
        return None
    records = {
        name: Record(signature, digest, racy)
        for name, (signature, digest, racy) in found.files.items()
    }
    records.update({name: Record(None) for name in found.absent})
    now = time.time_ns()
    # A pattern's folder by its names: a file that comes to match it (an SRDF beside the
    # description, a part a xacro glob includes) starts a build, as the fast path reruns.
    records.update({folder: record_now(folder, now) for folder in _pattern_folders(found.globs)})
    records.update({folder: record_now(folder, now) for folder in found.python_folders})
    package = str(Path(stamp.__file__).resolve().parents[1]) + os.sep
    code = {name for name in found.files if name.startswith(package)}
    code |= set(found.python_folders)
    return Watched(records, frozenset(code), frozenset(found.written))


def _pattern_folders(globs: dict[str, list[str]]) -> list[str]:
    """The folder of each file-name pattern (``a/srdf/*.srdf`` -> ``a/srdf/``), where its
    matches come and go; a pattern with a wildcard in a folder's name is watched from the
    folder above it."""
    import glob

    folders = set()
    for pattern in globs:
        parts = Path(pattern).parts
        fixed = next((i for i, part in enumerate(parts) if glob.has_magic(part)), len(parts))
        folders.add(os.path.join(*parts[:fixed], ""))
        # And every folder the pattern's folder part matches now (x_moveit_config/config/):
        # a file added in one changes no listing above it.
        folders.update(os.path.join(found, "") for found in glob.glob(os.path.dirname(pattern)))
    return sorted(folders)


def without_stamp(manifest: Path, last_good: Watched | None, before: Watched) -> Watched:
    """What to watch after a build of ``manifest`` that left no stamp (:func:`around`), each
    file as it was in ``before`` (taken when the build started) where it was there, and the
    outputs of ``last_good`` as they are now."""
    now = time.time_ns()
    records = {
        path: before.records.get(path) or record_now(path, now)
        for path in around(manifest, last_good)
    }
    if last_good is None:
        return Watched(records)
    # The outputs too, as the failed build left them: one it stopped at (edited by hand,
    # exit 7) is moved away or checked out to settle it, and that must start a build.
    for path in sorted(last_good.written):
        records.setdefault(path, record_now(path, now))
    return Watched(records, last_good.code, last_good.written)


def around(manifest: Path, last_good: Watched | None) -> list[str]:
    """The manifest, every file below its folder, its source's and its packages' folders
    (at most :data:`MOST_TREE_FILES` in all), and the files of ``last_good``, except what a
    build writes: output folders (below those folders, holding a state folder; the files
    builds recorded writing where one of those folders is an output folder itself), the
    files ``last_good`` lists as written, MuJoCo's log, and the files this process prints to."""
    outputs: list[str] = []
    recorded: set[str] = set()
    last_written = last_good.written if last_good is not None else frozenset()
    found = [str(manifest.resolve())]
    walked: list[Path] = []
    for folder in [manifest.resolve().parent, *declared_folders(manifest)]:
        if len(found) >= MOST_TREE_FILES or any(folder.is_relative_to(w) for w in walked):
            continue
        walked.append(folder)
        for top, folders, files in os.walk(folder):
            if STATE_DIR in folders and top != str(folder):
                outputs.append(top + os.sep)
                folders[:] = []
                continue
            if STATE_DIR in folders:  # the output folder is this folder itself
                recorded |= _recorded_as_written(Path(top))
            paths = [os.path.join(top, name) for name in files]
            if STATE_DIR not in folders and not any(
                path in recorded or path in last_written for path in paths
            ):  # not a folder builds write into: a file created here later is seen
                found.append(top + os.sep)
            folders[:] = sorted(name for name in folders if name not in SKIPPED | {STATE_DIR})
            found += [os.path.join(top, name) for name in sorted(files) if name != MUJOCO_LOG]
            if len(found) >= MOST_TREE_FILES:
                break
    written: set[str] = recorded
    if last_good is not None:
        found += last_good.records
        written |= last_good.written
    own = _own_output()
    return sorted(
        path
        for path in set(found)
        if path not in written
        and not path.startswith(tuple(outputs))
        and not (own and _identity(path) in own)
    )


def _own_output() -> set[tuple[int, int]]:
    """The files this process's output goes to (``mjcfbuild watch > watch.txt`` in the
    robot's folder), by device and inode: each line it prints would change one, and every
    change start another build, without end."""
    identities = set()
    for descriptor in (1, 2):
        try:
            stat = os.fstat(descriptor)
        except OSError:
            continue
        if S_ISREG(stat.st_mode):
            identities.add((stat.st_dev, stat.st_ino))
    return identities


def _identity(path: str) -> tuple[int, int] | None:
    stat = _stat(path)
    return None if stat is None else (stat.st_dev, stat.st_ino)


def _recorded_as_written(out_dir: Path) -> set[str]:
    """The files builds recorded writing in ``out_dir`` (its state folder's written.json,
    :mod:`mjcfbuild.engine.written`, which a failed build updates too), read plainly: none
    where it cannot be read."""
    import json

    try:
        files = json.loads((out_dir / STATE_DIR / WRITTEN).read_text(encoding="utf-8"))["files"]
    except (OSError, ValueError, TypeError, KeyError):
        return set()
    names = files if isinstance(files, list | dict) else []
    return {str(out_dir / name) for name in names if isinstance(name, str)}


def declared_folders(manifest: Path) -> list[Path]:
    """The folders ``manifest`` names, read as plainly as can be (it may be what failed): its
    source's folder and its packages' folders, relative to it; none where it cannot be read."""
    import yaml

    try:
        data = yaml.safe_load(manifest.read_text(encoding="utf-8"))
    except (OSError, UnicodeError, yaml.YAMLError):
        return []
    if not isinstance(data, dict):
        return []
    base = manifest.resolve().parent
    named: list[object] = []
    source, packages = data.get("source"), data.get("packages")
    if isinstance(source, dict):
        named += [Path(str(source[k])).parent for k in ("urdf", "xacro") if source.get(k)]
    if isinstance(packages, dict):
        named += list(packages.values())
    folders = []
    for entry in named:
        if isinstance(entry, str | Path):
            folder = (base / entry).resolve()
            if folder.is_dir() and folder not in folders:
                folders.append(folder)
    return folders


def record_now(path: str, now_ns: int) -> Record:
    """What ``path`` is at ``now_ns`` (``time.time_ns()``); a folder's (``path`` ends with
    os.sep) names too."""
    stat = _stat(path)
    if stat is None:
        return Record(None)
    listing = _listing(path) if path.endswith(os.sep) else None
    if not filesig.racy(stat, now_ns):
        return Record(filesig.signature(stat), listing=listing)
    return Record(filesig.signature(stat), _md5(path), racy=True, listing=listing)


def _listing(path: str) -> tuple[str, ...] | None:
    """The names of the files in the folder ``path``, but MuJoCo's log (None for a file, or
    a folder gone)."""
    if not path.endswith(os.sep):
        return None
    try:
        with os.scandir(path) as entries:
            return tuple(sorted(e.name for e in entries if e.name != MUJOCO_LOG and e.is_file()))
    except OSError:
        return None


def _stat(path: str) -> os.stat_result | None:
    try:
        return os.stat(path)
    except OSError:
        return None


def _md5(path: str) -> str | None:
    if path.endswith(os.sep):
        return None  # a folder: its names tell
    try:
        with open(path, "rb") as file:
            return hashlib.file_digest(file, "md5").hexdigest()
    except OSError:
        return None
