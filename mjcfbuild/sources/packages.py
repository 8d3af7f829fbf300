"""Finding ROS packages without ROS.

``package://pkg/...`` URIs and xacro's ``$(find pkg)`` need the folder of a package. It comes
from the manifest's ``packages`` map first, then from the environment the way ROS tools look:
``ROS_PACKAGE_PATH`` (ROS 1: folders crawled for ``package.xml``) and ``AMENT_PREFIX_PATH``
(ROS 2: ``<prefix>/share/<pkg>`` registered in the ament resource index).

The "did you mean" of every name a message says is missing (a package, a joint, a link, a
rule's pattern) and the listing of the names there are come from here too.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from pathlib import Path

from mjcfbuild.errors import InputError

# What robot.yaml's packages accept as a name: ROS's (REP 144), and the capitals, dashes and
# dots packages in the wild have.
PACKAGE_PATTERN = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")

ENV_VARIABLES = ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")
_IGNORE_MARKERS = ("CATKIN_IGNORE", "COLCON_IGNORE", "AMENT_IGNORE")
_MAX_CRAWL_DEPTH = 16


class PackageResolver:
    """Maps ROS package names to folders: the manifest first, then the ROS environment."""

    def __init__(self, explicit: Mapping[str, Path], environ: Mapping[str, str]) -> None:
        self.explicit = {name: Path(folder) for name, folder in explicit.items()}
        self.environ = {key: environ.get(key, "") for key in ENV_VARIABLES}
        self._crawled: dict[str, Path] | None = None

    def fingerprint(self) -> dict[str, object]:
        """Everything resolution depends on, for a task's up-to-date check."""
        return {
            "packages": {name: str(path) for name, path in sorted(self.explicit.items())},
            "environment": dict(self.environ),
        }

    def find(self, name: str) -> Path:
        """The folder of package ``name``; :class:`InputError` listing known packages if none."""
        if name in self.explicit:
            folder = self.explicit[name]
            if not folder.is_dir():
                raise InputError(
                    f"package '{name}' points at '{folder}', which is not a folder",
                    hint="fix its entry under 'packages' in robot.yaml",
                )
            return folder
        found = self._find_in_ament(name) or self._find_in_ros_package_path(name)
        if found is not None:
            return found
        if not PACKAGE_PATTERN.match(name):
            raise InputError(
                f"'{name}' is no ROS package name (letters, digits, '_', '-' and '.'), so no "
                "package provides it",
                hint="fix the package:// or $(find) that names it",
            )
        known = sorted(set(self.explicit) | set(self._crawl()))
        listing = ", ".join(known) if known else "none"
        raise InputError(
            f"unknown package '{name}'{did_you_mean(name, known)} (known packages: {listing})",
            hint=f"add '{name}: <folder>' under 'packages' in robot.yaml, "
            "or set ROS_PACKAGE_PATH / AMENT_PREFIX_PATH",
        )

    def _find_in_ament(self, name: str) -> Path | None:
        for prefix in _split(self.environ["AMENT_PREFIX_PATH"]):
            share = Path(prefix) / "share"
            marker = share / "ament_index" / "resource_index" / "packages" / name
            folder = share / name
            if (marker.exists() or (folder / "package.xml").is_file()) and folder.is_dir():
                return folder
        return None

    def _find_in_ros_package_path(self, name: str) -> Path | None:
        return self._crawl().get(name)

    def _crawl(self) -> dict[str, Path]:
        """Every package below ROS_PACKAGE_PATH, by name; the first one found wins."""
        if self._crawled is None:
            self._crawled = {}
            seen: set[str] = set()
            for root in _split(self.environ["ROS_PACKAGE_PATH"]):
                _crawl_folder(Path(root), 0, self._crawled, seen)
        return self._crawled


def environment_index(environ: Mapping[str, str]) -> str:
    """A digest of what ``environ``'s AMENT_PREFIX_PATH and ROS_PACKAGE_PATH offer package
    lookup, in their order: each prefix's ament index and ``share/`` names, and the
    ``package.xml`` files the crawl of ROS_PACKAGE_PATH meets. A package that comes to shadow
    another (built into an overlay already on the path, copied into an earlier folder) changes
    it, though neither variable does. Folder listings only, no file read: the no-op build
    computes it. Empty where neither variable is set."""
    import hashlib

    ament, ros = environ.get("AMENT_PREFIX_PATH", ""), environ.get("ROS_PACKAGE_PATH", "")
    if not ament and not ros:
        return ""
    lines: list[str] = []
    for prefix in _split(ament):
        share = Path(prefix) / "share"
        for folder in (share / "ament_index" / "resource_index" / "packages", share):
            lines.append(f"{folder}\0" + "\0".join(sorted(_names_in(folder))))
    seen: set[str] = set()
    for root in _split(ros):
        _package_files(Path(root), 0, lines, seen)
    return hashlib.sha256("\n".join(lines).encode()).hexdigest()[:32]


def _names_in(folder: Path) -> set[str]:
    try:
        with os.scandir(folder) as entries:
            return {entry.name for entry in entries}
    except OSError:
        return set()


def _package_files(folder: Path, depth: int, found: list[str], seen: set[str]) -> None:
    """The ``package.xml`` files the crawl of ROS_PACKAGE_PATH meets in and below ``folder``
    (:func:`_crawl_folder`'s walk, without reading them)."""
    real = os.path.realpath(folder)
    if real in seen:
        return
    seen.add(real)
    manifest = folder / "package.xml"
    if manifest.is_file():
        found.append(str(manifest))
        return
    if depth >= _MAX_CRAWL_DEPTH or any((folder / m).exists() for m in _IGNORE_MARKERS):
        return
    names = sorted(name for name in _names_in(folder) if not name.startswith("."))
    for name in names:
        child = folder / name
        if child.is_dir():
            _package_files(child, depth + 1, found, seen)


def _split(value: str) -> list[str]:
    return [part for part in value.split(os.pathsep) if part]


def _crawl_folder(folder: Path, depth: int, found: dict[str, Path], seen: set[str]) -> None:
    """Add the packages in and below ``folder`` to ``found``, as rospack crawls: into linked
    folders too (a package linked into a workspace's src/ is a common layout), each real
    folder once (``seen``), not below a package or a folder marked to be ignored."""
    real = os.path.realpath(folder)
    if real in seen:
        return
    seen.add(real)
    manifest = folder / "package.xml"
    if manifest.is_file():
        found.setdefault(package_name(manifest) or folder.name, folder)
        return
    if depth >= _MAX_CRAWL_DEPTH or any((folder / m).exists() for m in _IGNORE_MARKERS):
        return
    try:
        children = sorted(entry for entry in folder.iterdir() if not entry.name.startswith("."))
    except OSError:
        return
    for child in children:
        if child.is_dir():
            _crawl_folder(child, depth + 1, found, seen)


def package_name(package_xml: Path) -> str | None:
    """The ``<name>`` of a ``package.xml``: the first ``name`` child of its ``<package>``, read
    as XML, so a ``<name>`` inside a comment (``<!-- renamed from <name>old</name> -->``) or
    another element is not taken for it; None when the file is unreadable, not XML or has no
    name."""
    from lxml import etree

    try:
        data = package_xml.read_bytes()
    except OSError:
        return None
    parser = etree.XMLParser(
        resolve_entities=False, no_network=True, remove_comments=True, recover=False
    )
    try:
        root = etree.fromstring(data, parser)
    except (etree.XMLSyntaxError, ValueError):
        return None
    if etree.QName(root).localname != "package":
        return None
    for child in root:
        if isinstance(child.tag, str) and etree.QName(child).localname == "name":
            name = (child.text or "").strip()
            return name or None
    return None


def find_enclosing_package(path: Path) -> tuple[str, Path] | None:
    """The ROS package a file lives in (name and folder), found by walking up to package.xml."""
    for folder in [path, *path.parents] if path.is_dir() else path.parents:
        manifest = folder / "package.xml"
        if manifest.is_file():
            return package_name(manifest) or folder.name, folder
    return None


def did_you_mean(name: str, candidates: list[str] | set[str]) -> str:
    """``; did you mean 'x'?`` for the candidate closest to ``name``, or nothing.

    A candidate is offered when it is one edit away ('j2' for 'j1'), or similar as difflib
    measures it and within a few edits for its length: 'head' shares letters with 'r_hand'
    but is three edits from it, a suggestion that sends a user the wrong way."""
    import difflib

    others = sorted(set(candidates) - {name})
    close = [
        c
        for c in difflib.get_close_matches(name, others, n=3)
        if _edits(name, c) <= len(name) // 3 + 1
    ]
    near = [c for c in others if len(name) > 1 and _edits(name, c) == 1]
    match = (close or near)[:1]
    return f"; did you mean '{match[0]}'?" if match else ""


def within_edits(name: str, candidates: list[str] | set[str], edits: int) -> bool:
    """Whether a candidate other than ``name`` is at most ``edits`` edits from it, and at
    most half its length ('prat' for 'part'; but 'x' is one edit from any one-letter name, and
    a name of two letters two from any other: typos of none)."""
    most = min(edits, len(name) // 2) if len(name) > 2 else 0
    return most > 0 and any(_edits(name, c) <= most for c in set(candidates) - {name})


def _edits(a: str, b: str) -> int:
    """The Levenshtein distance between ``a`` and ``b``."""
    previous = list(range(len(b) + 1))
    for i, x in enumerate(a, 1):
        current = [i]
        for j, y in enumerate(b, 1):
            current.append(min(previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (x != y)))
        previous = current
    return previous[-1]


def suggestion(patterns: list[str], names: list[str]) -> str:
    """``; did you mean 'x'?`` for the name closest to one of ``patterns`` (a glob pattern
    compared without its wildcards), or nothing."""
    import re

    for pattern in patterns:
        found = did_you_mean(pattern, names) or did_you_mean(pattern.strip("*?"), names)
        if found:
            return found
    # A pattern's word misspelt ('*fingr*' among 'left_finger_joint', ...): the pattern with
    # the closest word of the names in its place.
    words = sorted({word for name in names for word in re.split(r"[_\-.]", name) if word})
    for pattern in patterns:
        core = pattern.strip("*?")
        if not core or core == pattern or not re.fullmatch(r"[\w\-.]+", core):
            continue
        found = did_you_mean(core, words)
        if found:
            word = found.split("'")[1]
            return f"; did you mean '{pattern.replace(core, word)}'?"
    return ""


def listing(names: list[str], most: int = 12) -> str:
    """Names for an error message's hint, the first ``most`` of them."""
    shown = ", ".join(names[:most])
    return (
        shown + (f", ... ({len(names)} in all)" if len(names) > most else "") if names else "none"
    )
