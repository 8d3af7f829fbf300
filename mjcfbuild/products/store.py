"""The shared cache of build products: converted meshes and convex decompositions, and the
one-file products of other steps (the collision matrix, the reference kinematics, pictures).

A product is stored under a key made of everything it depends on: the bytes of its inputs,
the step's parameters, the step's format and the versions of the tools it used. Any build of
any manifest, in any output folder, that needs the same product finds it here instead of
recomputing it; a fresh clone of a description repo does not decompose again.

Layout: ``<cache>/products/<key[:2]>/<key>/`` holds the product's files and ``summary.json``.
Entries are written to a temporary folder and renamed into place, so a killed build never
leaves a half-written entry. Using an entry refreshes its modification time; pruning removes
the least recently used entries until the cache fits its size cap. Measuring the cache means
a stat of every file of every entry (0.12 s for 1,800 entries here, more on a slow disk), so
a build does it only when the cache may have outgrown its cap or an hour has passed: the last
measurement is kept in ``.usage.json`` and each entry stored since adds a line with its size
to ``.added`` (:meth:`ProductStore.prune_if_full`). A product is checked for
use (mjcfbuild.products.usable) before it is stored and before it is used: an unusable entry is
removed and the step computes the product again, so nothing in the cache can fail a build.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import time
import uuid
from dataclasses import dataclass
from pathlib import Path

from mjcfbuild.cachedir import (  # noqa: F401 (the cache size is settled there, for the CLI)
    DEFAULT_MAX_BYTES,
    MAX_VARIABLE,
    default_max_bytes,
    parse_size,
    user_cache_dir,
)
from mjcfbuild.fsutil import atomic_write, md5_file
from mjcfbuild.products.usable import product_problem

_SUMMARY = "summary.json"
_USAGE = ".usage.json"  # {"bytes": the cache's size when last measured, "measured": when}
_ADDED = ".added"  # the size of each entry stored since, one per line
# How long a measurement is trusted: what other programs did to the folder (a user's rm, a
# build killed while storing) is seen within this time.
REMEASURE_SECONDS = 3600.0


def default_cache_folder() -> Path:
    """The product cache inside the user cache folder."""
    return user_cache_dir() / "products"


def open_store(settings: dict) -> ProductStore | None:
    """The store a build step should use, from the payload's cache settings (None: off)."""
    if not settings.get("enabled"):
        return None
    return ProductStore(Path(settings["folder"]), settings["max_bytes"])


def product_key(step: str, params: dict, input_files: list[str | Path]) -> str:
    """The cache key of a product: its step, parameters and the bytes of its inputs."""
    digest = hashlib.sha256()
    digest.update(json.dumps({"step": step, "params": params}, sort_keys=True).encode())
    for path in input_files:
        digest.update(md5_file(path).encode())
    return digest.hexdigest()


@dataclass
class CacheUsage:
    """How big the cache is."""

    folder: Path
    entries: int
    bytes: int


class ProductStore:
    """Products by key in a folder shared by every build."""

    def __init__(self, folder: Path | None = None, max_bytes: int | None = None) -> None:
        self.folder = Path(folder) if folder is not None else default_cache_folder()
        self.max_bytes = default_max_bytes() if max_bytes is None else max_bytes
        # (key, why) of each unusable entry :meth:`fetch` found and removed
        self.dropped: list[tuple[str, str]] = []

    def _entry(self, key: str) -> Path:
        return self.folder / key[:2] / key

    def fetch(self, key: str, destination: Path, kind: str | None = None) -> dict | None:
        """Copy the product ``key`` (of ``kind``: see :func:`product_problem`) into
        ``destination`` (replacing its files); its summary. None when there is none, or the
        entry cannot be used: such an entry is removed and recorded in :attr:`dropped`."""
        entry = self._entry(key)
        summary = self._usable_summary(key, kind)
        if summary is None:
            return None
        destination.mkdir(parents=True, exist_ok=True)
        wanted = set(summary["files"])
        for stale in destination.iterdir():
            if stale.name not in wanted:
                stale.unlink()
        try:
            for name in wanted:
                _link_or_copy(entry / name, destination / name)
        except OSError:
            return None
        self._touch(key)
        return summary

    def _usable_summary(self, key: str, kind: str | None) -> dict | None:
        """The summary of the entry ``key`` if it can be used as a product of ``kind``; None
        when there is no entry, or it cannot be used (it is removed and recorded)."""
        entry = self._entry(key)
        try:
            summary = json.loads((entry / _SUMMARY).read_text())
        except FileNotFoundError:
            return None
        except (OSError, ValueError):
            summary = None
        problem = product_problem(kind, summary, entry)
        if problem is not None:
            self._drop(key, problem)
            return None
        return summary

    def _touch(self, key: str) -> None:
        """Mark the entry ``key`` used now (pruning removes the least recently used)."""
        with contextlib.suppress(OSError):  # a read-only cache: the entry just ages
            now = time.time()
            os.utime(self._entry(key) / _SUMMARY, (now, now))

    def fetch_file(self, key: str, name: str, kind: str) -> bytes | None:
        """The bytes of the one-file product ``key`` of ``kind``, whose file is ``name``; None
        when there is none or it cannot be used (as :meth:`fetch`)."""
        if self._usable_summary(key, kind) is None:
            return None
        try:  # checked against its digest by _usable_summary
            data = (self._entry(key) / name).read_bytes()
        except OSError:  # pruned by another build since
            return None
        self._touch(key)
        return data

    def store_file(self, key: str, name: str, data: bytes, kind: str) -> bool:
        """Add a one-file product: ``data`` as its file ``name``; as :meth:`store` (a full or
        read-only cache stores nothing and never fails a build)."""
        folder = self.temporary_folder(key)
        try:
            folder.mkdir(parents=True)
            (folder / name).write_bytes(data)
            return self.store(key, folder, {"files": {name: md5_file(folder / name)}}, kind)
        except OSError:
            return False
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def _drop(self, key: str, problem: str) -> None:
        """Remove the unusable entry ``key`` (if the cache can be written) and remember why."""
        self.dropped.append((key, problem))
        shutil.rmtree(self._entry(key), ignore_errors=True)

    def has(self, key: str) -> bool:
        """Whether the product ``key`` is here."""
        return (self._entry(key) / _SUMMARY).is_file()

    def read(self, key: str) -> tuple[Path, dict] | None:
        """The folder and summary of the product ``key``, without copying it anywhere."""
        entry = self._entry(key)
        try:
            return entry, json.loads((entry / _SUMMARY).read_text())
        except (OSError, ValueError):
            return None

    def temporary_folder(self, key: str) -> Path:
        """A fresh folder to assemble the product ``key`` in before :meth:`store` (removed by
        the caller; a killed build's leftovers are removed by :meth:`prune`)."""
        return self._entry(key).parent / f".{key}.{uuid.uuid4().hex}.tmp"

    def store(self, key: str, source: Path, summary: dict, kind: str | None = None) -> bool:
        """Add a product (the files listed in ``summary['files']`` in ``source``); whether the
        cache holds it now. A product that cannot be used (see :func:`product_problem`) is
        never stored; a full or read-only cache stores nothing and never fails a build."""
        entry = self._entry(key)
        if (entry / _SUMMARY).exists():
            return True
        if product_problem(kind, summary, source) is not None:
            return False
        temporary = entry.parent / f".{key}.{uuid.uuid4().hex}.tmp"
        try:
            temporary.mkdir(parents=True)
            for name in summary.get("files", {}):
                _link_or_copy(source / name, temporary / name)
            (temporary / _SUMMARY).write_text(json.dumps(summary, sort_keys=True))
            size = _folder_bytes(temporary)
            os.replace(temporary, entry)
        except OSError:
            return False  # a full or read-only cache must never fail a build
        finally:
            if temporary.exists():
                shutil.rmtree(temporary, ignore_errors=True)
        self._note_added(size)
        return True

    def _note_added(self, size: int) -> None:
        """Add an entry's ``size`` to what :meth:`estimated_bytes` counts on."""
        with contextlib.suppress(OSError):
            # One short line with O_APPEND: builds storing at once do not mix their lines.
            fd = os.open(self.folder / _ADDED, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
            try:
                os.write(fd, f"{size}\n".encode())
            finally:
                os.close(fd)

    def usage(self) -> CacheUsage:
        """Number of entries and bytes used."""
        entries = self._entries()
        return CacheUsage(self.folder, len(entries), sum(size for _, _, size in entries))

    def prune(self, max_bytes: int | None = None) -> int:
        """Remove least recently used entries until the cache fits; the number removed."""
        limit = self.max_bytes if max_bytes is None else max_bytes
        entries = sorted(self._entries(), key=lambda item: item[1])
        total = sum(size for _, _, size in entries)
        removed = 0
        for path, _, size in entries:
            if total <= limit:
                break
            shutil.rmtree(path, ignore_errors=True)
            total -= size
            removed += 1
        self._record_usage(total)
        return removed

    def prune_if_full(self) -> int:
        """:meth:`prune`, unless the last measurement plus what was stored since fits the cap
        and is under :data:`REMEASURE_SECONDS` old; the number of entries removed."""
        estimate = self.estimated_bytes()
        if estimate is not None and estimate <= self.max_bytes:
            return 0
        return self.prune()

    def estimated_bytes(self) -> int | None:
        """The size at the last measurement plus the entries stored since; None when there is
        no recent measurement to go by."""
        try:
            usage = json.loads((self.folder / _USAGE).read_text())
            measured, size = float(usage["measured"]), int(usage["bytes"])
        except (OSError, ValueError, KeyError, TypeError):
            return None
        if not 0 <= time.time() - measured < REMEASURE_SECONDS:
            return None
        try:
            added = (self.folder / _ADDED).read_text().split()
        except FileNotFoundError:
            added = []
        except OSError:
            return None
        try:
            return size + sum(int(line) for line in added)
        except ValueError:  # a torn line: measure again
            return None

    def _record_usage(self, size: int) -> None:
        """Keep ``size`` as the measurement :meth:`estimated_bytes` starts from. An entry
        stored while the cache was being measured may be left out of it; the next
        measurement, at most an hour later, counts it."""
        with contextlib.suppress(OSError):  # a read-only cache is measured every time
            (self.folder / _ADDED).unlink(missing_ok=True)
            record = {"bytes": size, "measured": time.time()}
            atomic_write(self.folder / _USAGE, json.dumps(record).encode())

    def clear(self) -> int:
        """Remove every entry; the number removed."""
        entries = self._entries()
        for path, _, _ in entries:
            shutil.rmtree(path, ignore_errors=True)
        return len(entries)

    def _entries(self) -> list[tuple[Path, float, int]]:
        result: list[tuple[Path, float, int]] = []
        if not self.folder.is_dir():
            return result
        stale_before = time.time() - 3600
        for bucket in self.folder.iterdir():
            if not bucket.is_dir():
                continue
            for entry in bucket.iterdir():
                summary = entry / _SUMMARY
                if entry.name.startswith("."):
                    # A half-written entry of a build that was killed an hour or more ago.
                    if entry.name.endswith(".tmp") and entry.stat().st_mtime < stale_before:
                        shutil.rmtree(entry, ignore_errors=True)
                    continue
                if not summary.exists():
                    continue
                result.append((entry, summary.stat().st_mtime, _folder_bytes(entry)))
        return result


def _folder_bytes(folder: Path) -> int:
    """The bytes of the files in ``folder`` (not below it)."""
    return sum(f.stat().st_size for f in folder.iterdir() if f.is_file())


def _link_or_copy(source: Path, target: Path) -> None:
    """Hard-link ``source`` to ``target`` (same file system), else copy it."""
    target.unlink(missing_ok=True)
    try:
        os.link(source, target)
    except OSError:
        shutil.copyfile(source, target)
