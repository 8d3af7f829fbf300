"""Content hashes of files, remembered by their stat signature so unchanged files are not re-read.

doit's stock MD5 checker re-hashes every file whose mtime moved, on every run, until the task
runs again. A fresh git checkout or a ``touch`` moves every mtime, so that would re-read every
mesh on every no-op build. This cache records the hash of each file against its signature
(:func:`mjcfbuild.filesig.signature`: size, mtime, ctime, inode, device); a file whose
signature is unchanged is not read again. Files changed within the file system's timestamp
tick (:func:`mjcfbuild.filesig.racy`) are hashed but not remembered, so a write within the
file system's timestamp granularity is never missed.
"""

from __future__ import annotations

import json
import os
import threading
import time
from pathlib import Path

from mjcfbuild.filesig import racy, signature
from mjcfbuild.fsutil import atomic_write, md5_file


class HashCache:
    """MD5 of files by path, persisted as JSON in the build's state folder."""

    def __init__(self, path: Path | None) -> None:
        self.path = path
        self._entries: dict[str, list] = {}
        self._dirty = False
        self._lock = threading.Lock()
        if path is not None:
            try:
                self._entries = json.loads(path.read_text())
            except (OSError, ValueError):
                self._entries = {}

    def md5(self, file: str | os.PathLike, stat: os.stat_result | None = None) -> str:
        """The MD5 of ``file``; raises OSError if it cannot be read."""
        key = os.fspath(file)
        stat = stat or os.stat(key)
        known = signature(stat)
        with self._lock:
            entry = self._entries.get(key)
            # An entry of an older format (without ctime and device) never matches.
            if entry is not None and entry[:-1] == known:
                return entry[-1]
        digest = md5_file(key)
        if not racy(stat, time.time_ns()):
            with self._lock:
                self._entries[key] = [*known, digest]
                self._dirty = True
        return digest

    def save(self) -> None:
        """Write the cache back if it changed, dropping entries of files that are gone; not
        where its folder is gone (removed during the build, which then fails saying so)."""
        if self.path is None or not self._dirty or not self.path.parent.is_dir():
            return
        with self._lock:
            entries = {k: v for k, v in sorted(self._entries.items()) if os.path.exists(k)}
            self._dirty = False
        atomic_write(self.path, json.dumps(entries, separators=(",", ":")).encode())
