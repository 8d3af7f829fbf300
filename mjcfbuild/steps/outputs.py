"""Helpers shared by build steps for writing and reporting their outputs."""

from __future__ import annotations

import hashlib
from pathlib import Path

from mjcfbuild.fsutil import md5_file, write_if_changed
from mjcfbuild.ownership import note_written, refuse_foreign


def write_output(path: Path, data: bytes, outputs: dict[str, str]) -> None:
    """Write ``data`` to ``path`` (atomically, only if different) and record its hash, in the
    step's outputs and the output folder's journal; a file of the user's found in the output
    folder is never written over (mjcfbuild.ownership)."""
    refuse_foreign(path, data)
    path.parent.mkdir(parents=True, exist_ok=True)
    digest = hashlib.md5(data, usedforsecurity=False).hexdigest()
    note_written(path, digest)  # first: a write cut short by a kill is the build's, not an edit
    write_if_changed(path, data)
    outputs[str(path)] = digest


def record_output(path: Path, outputs: dict[str, str]) -> None:
    """Record the hash of a file a step wrote by other means."""
    outputs[str(path)] = md5_file(path)
