"""Finding the packages a description names (for ``mjcfbuild init``): by their ``package.xml``
first, else by the files the description names in them.

Description folders shipped in wheels or copied out of a ROS workspace (jvrc-, icub- or
upkie-style) often keep the package's folder without its ``package.xml``. The ``package://``
URIs and ``$(find ...)`` paths still say which files each package holds, so the folder is the
nearest one, beside or above the description, that holds them.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

_REFERENCE = re.compile(
    rb"(?:package://([A-Za-z0-9_.-]+)|\$\(find\s+([A-Za-z0-9_.-]+)\))/([^\"'\s<>$]+)"
)
_LEVELS = 6  # how far above the description to look


@dataclass(frozen=True)
class InferredPackage:
    """A package folder found from the files the description names in it."""

    folder: Path
    evidence: str  # one file of the package that is there, as the description names it
    package_xml: str | None = None  # the name the folder's package.xml gives, if it has one


def package_references(data: bytes) -> dict[str, list[str]]:
    """Per package name, the paths inside it the description names (without ``${...}``)."""
    found: dict[str, list[str]] = {}
    for match in _REFERENCE.finditer(data):
        name = (match.group(1) or match.group(2)).decode()
        path = match.group(3).decode()
        if "${" not in path and path not in found.setdefault(name, []):
            found[name].append(path)
    return found


def find_package_xml(name: str, source: Path) -> list[Path]:
    """The folders of every ``package.xml`` naming package ``name``, nearest first, among the
    folders above ``source`` and their children (a package beside the description's own, in
    one workspace). More than one is a workspace catkin and colcon refuse to build."""
    from mjcfbuild.sources.packages import package_name

    found: list[Path] = []
    for ancestor in list(source.resolve().parents)[:_LEVELS]:
        try:
            children = sorted(child for child in ancestor.iterdir() if child.is_dir())
        except OSError:
            continue
        for folder in [ancestor, *children]:
            manifest = folder / "package.xml"
            if folder not in found and manifest.is_file() and package_name(manifest) == name:
                found.append(folder)
    return found


def infer_package(name: str, paths: list[str], source: Path) -> InferredPackage | None:
    """The folder of package ``name``: the nearest folder, among those above ``source`` and
    their children called ``name``, holding every path of ``paths`` (or, failing that, the
    nearest holding any of them)."""
    candidates = []
    for ancestor in list(source.resolve().parents)[:_LEVELS]:
        candidates += [ancestor / name, ancestor]
    partial = None
    for folder in candidates:
        present = [p for p in paths if (folder / p).is_file()]
        if present and len(present) == len(paths):
            return _inferred(folder, present[0])
        if present and partial is None:
            partial = _inferred(folder, present[0])
    return partial


def _inferred(folder: Path, evidence: str) -> InferredPackage:
    from mjcfbuild.sources.packages import package_name

    manifest = folder / "package.xml"
    declared = (package_name(manifest) or folder.name) if manifest.is_file() else None
    return InferredPackage(folder, evidence, declared)
