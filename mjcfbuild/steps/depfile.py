"""Dependencies only known after a step ran, like the files a xacro expansion included.

A step that discovers its inputs records them in a *depfile* next to its output (the idea of
make's and ninja's ``.d`` files): the files it read, the files it looked for and did not find,
the environment variables it read, and the file-name patterns it listed (a xacro include of
``parts/*.xacro``) with the files each matched. The next build declares those files as the task's
dependencies and reruns the task when a missing file appeared or a variable changed. The set
of files a step reads only changes when one of the files it read changed, so the previous
run's list is always the right one to check.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from mjcfbuild.fsutil import atomic_write


@dataclass
class Depfile:
    """What a step read."""

    files: list[str] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    environment: dict[str, str | None] = field(default_factory=dict)
    globs: dict[str, list[str]] = field(default_factory=dict)  # pattern -> the files it matched

    def write(self, path: Path) -> None:
        """Store it (atomically, sorted, so equal content gives equal bytes)."""
        data: dict[str, object] = {
            "files": sorted(set(self.files)),
            "missing": sorted(set(self.missing)),
            "environment": dict(sorted(self.environment.items())),
        }
        if self.globs:
            data["globs"] = {pattern: sorted(set(m)) for pattern, m in sorted(self.globs.items())}
        atomic_write(path, (json.dumps(data, indent=1) + "\n").encode())

    @staticmethod
    def read(path: Path) -> Depfile | None:
        """The depfile at ``path``, or None if there is none (or it is unreadable)."""
        try:
            data = json.loads(path.read_text())
            globs = {str(p): [str(m) for m in found] for p, found in data.get("globs", {}).items()}
            return Depfile(
                list(data["files"]), list(data["missing"]), dict(data["environment"]), globs
            )
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            return None

    def stale_reason(self, environ: Mapping[str, str]) -> str | None:
        """Why the recorded dependencies no longer hold without looking at file contents."""
        for name in self.files:
            if not os.path.exists(name):
                return f"{name} was removed"
        for name in self.missing:
            if os.path.exists(name):
                return f"{name} now exists"
        for variable, value in self.environment.items():
            if environ.get(variable) != value:
                return f"environment variable {variable} changed"
        changed = globs_changed(self.globs)
        if changed:
            return f"the files matching {changed} changed"
        return None


def globs_changed(globs: Mapping[str, list[str]]) -> str | None:
    """The first pattern of ``globs`` whose files are not the recorded ones any more (one was
    added or removed), if any."""
    import glob

    for pattern, matched in sorted(globs.items()):
        if sorted(glob.glob(pattern)) != sorted(matched):
            return pattern
    return None
