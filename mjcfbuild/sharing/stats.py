"""What a build got from where: counters for the report and ``mjcfbuild cache show``."""

from __future__ import annotations

import contextlib
import fcntl
import json
import threading
import time
from pathlib import Path

from mjcfbuild.fsutil import atomic_write

STATS_FILE = "remote-stats.json"
COUNTERS = (
    "local_hits",
    "local_dropped",
    "remote_hits",
    "remote_misses",
    "remote_rejected",
    "remote_errors",
    "uploaded",
    "computed_here",
    "computed_on_cluster",
)


class ShareStats:
    """Thread-safe counters of one build, by product kind where it matters."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._counts: dict[str, int] = dict.fromkeys(COUNTERS, 0)
        self._computed: dict[str, dict[str, int]] = {}

    def count(self, name: str, amount: int = 1) -> None:
        """Add ``amount`` to the counter ``name``."""
        with self._lock:
            self._counts[name] += amount

    def computed(self, kind: str, where: str) -> None:
        """A product of ``kind`` (mesh, decompose) was computed ``where`` (here, on_cluster)."""
        with self._lock:
            self._counts[f"computed_{where}"] += 1
            by_kind = self._computed.setdefault(kind, {"here": 0, "on_cluster": 0})
            by_kind[where] += 1

    def as_dict(self) -> dict:
        """The counters as plain data."""
        with self._lock:
            data: dict = dict(self._counts)
            data["computed"] = {kind: dict(v) for kind, v in sorted(self._computed.items())}
        return data


def record(cache_folder: Path, remote: str, build: dict) -> None:
    """Add a build's remote counters to the cache folder's totals (for ``cache show``)."""
    path = cache_folder / STATS_FILE
    try:
        cache_folder.mkdir(parents=True, exist_ok=True)
        with open(cache_folder / f".{STATS_FILE}.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            stats = read(cache_folder)
            entry = stats.setdefault(remote, {"total": dict.fromkeys(COUNTERS, 0)})
            for name in COUNTERS:
                entry["total"][name] = entry["total"].get(name, 0) + build.get(name, 0)
            entry["last_build"] = {name: build.get(name, 0) for name in COUNTERS}
            entry["updated"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
            atomic_write(path, (json.dumps(stats, indent=1, sort_keys=True) + "\n").encode())
    except OSError:
        pass  # counters are information; a read-only cache must not fail a build


def read(cache_folder: Path) -> dict:
    """The recorded counters, by remote address."""
    with contextlib.suppress(OSError, ValueError):
        data = json.loads((cache_folder / STATS_FILE).read_text())
        if isinstance(data, dict):
            return data
    return {}
