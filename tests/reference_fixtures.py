"""Where the reference converter's demo and its own output live: ``shared/fixtures/
reference_demo`` beside the checkout (CI has it at ``../shared``), at any depth above it, or
wherever ``MJCFBUILD_REFERENCE_DEMO`` says."""

from __future__ import annotations

import os
from pathlib import Path

RELATIVE = Path("shared") / "fixtures" / "reference_demo"
MARKER = Path("reference_output") / "scene.xml"


def candidates(start: Path) -> list[Path]:
    """The folders looked at, in order, for a checkout (or working folder) at ``start``."""
    found = []
    if os.environ.get("MJCFBUILD_REFERENCE_DEMO"):
        found.append(Path(os.environ["MJCFBUILD_REFERENCE_DEMO"]))
    for folder in [start.resolve(), *start.resolve().parents]:
        found.append(folder / RELATIVE)
    return found


def find_reference_demo(*starts: Path) -> Path | None:
    """The first reference_demo folder with the reference output in it, or None."""
    for start in starts:
        for folder in candidates(start):
            if (folder / MARKER).is_file():
                return folder
    return None
