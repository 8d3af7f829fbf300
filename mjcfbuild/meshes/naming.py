"""Short, stable, unique names for the mesh files a robot uses.

A mesh is named after its file stem. Files that share a stem (``visual/link0.dae`` and
``collision/link0.stl``) take as many of their folder names in front as it takes to tell them
apart, and no more, so names never carry the machine-specific start of an absolute path.
Names are compared without case, because asset files must not collide on case-insensitive file
systems. They depend only on the set of paths, never on the order they were met in.
"""

from __future__ import annotations

import re
from collections import defaultdict
from pathlib import PurePath

_UNSAFE = re.compile(r"[^A-Za-z0-9_-]+")


def sanitise(text: str) -> str:
    """A name made of letters, digits, '_' and '-' only."""
    cleaned = _UNSAFE.sub("_", text).strip("_")
    return cleaned or "mesh"


def assign_mesh_ids(paths: list[str]) -> dict[str, str]:
    """A unique name for every distinct path."""
    unique = sorted(set(paths))
    parts = {
        path: [sanitise(p).lower() for p in PurePath(path).with_suffix("").parts if p != "/"]
        for path in unique
    }
    shown = {
        path: [sanitise(p) for p in PurePath(path).with_suffix("").parts if p != "/"]
        for path in unique
    }
    depth = dict.fromkeys(unique, 1)
    for _ in range(64):
        groups: dict[str, list[str]] = defaultdict(list)
        for path in unique:
            groups["_".join(parts[path][-depth[path] :])].append(path)
        clashes = [group for group in groups.values() if len(group) > 1]
        if not clashes:
            break
        progressed = False
        for group in clashes:
            for path in group:
                needed = _distinguishing_depth(path, group, parts)
                if needed is not None and needed > depth[path]:
                    depth[path] = needed
                    progressed = True
        if not progressed:
            break
    names = {path: "_".join(shown[path][-depth[path] :]) for path in unique}
    # Paths that differ only in the case of their suffix: number them in path order.
    by_name: dict[str, list[str]] = defaultdict(list)
    for path in unique:
        by_name[names[path].lower()].append(path)
    for group in by_name.values():
        for index, path in enumerate(sorted(group)[1:], start=2):
            names[path] = f"{names[path]}_{index}"
    return names


def _distinguishing_depth(path: str, group: list[str], parts: dict[str, list[str]]) -> int | None:
    """How many trailing path parts tell ``path`` apart from the rest of ``group``."""
    mine = parts[path]
    for depth in range(1, len(mine) + 1):
        tail = mine[-depth:]
        if all(parts[other][-depth:] != tail for other in group if other != path):
            return depth
    return None
