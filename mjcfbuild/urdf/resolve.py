"""Resolving every file a parsed URDF refers to, and naming its meshes."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import NamedTuple

from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import case_match, case_suggestion, normalise, unreadable_file
from mjcfbuild.meshes.formats import MESH_FORMATS, mesh_format
from mjcfbuild.meshes.naming import assign_mesh_ids
from mjcfbuild.meshes.prebuilt import prebuilt_mesh
from mjcfbuild.sources.packages import PackageResolver, find_enclosing_package
from mjcfbuild.sources.uris import resolve_uri, uri_package_folder
from mjcfbuild.urdf.model import Robot, Shape


def resolve_files(
    robot: Robot,
    base_dir: Path,
    packages: PackageResolver,
    prebuilt: Path | None = None,
    roots: Sequence[Path] | None = None,
    outside: list[OutsideRead] | None = None,
) -> dict[str, str]:
    """Fill in the real path of every mesh and texture, and give each mesh file an id.

    Relative references are relative to ``base_dir``, the folder of the URDF or xacro file.
    A reference that cannot be resolved, a missing file or an unsupported format is an
    :class:`InputError` at the line of the element that names it. With ``prebuilt``, a
    folder of meshes converted before, a mesh with a pre-generated OBJ there is read from it.
    With ``roots`` (the folders the description may read: robot.yaml's, its packages'), a
    file outside them and outside every package a URI names gets a warning in
    ``robot.warnings``, once per URI, and is added to ``outside`` where given. Returns the
    mesh file each pre-generated OBJ stands for (a visual's where several do), whose look it
    takes where it has none of its own.
    """
    reads: list[tuple[str, Path, int | None]] = []
    mesh_paths: list[str] = []
    originals: dict[str, str] = {}  # pre-generated OBJ -> the mesh file it stands for
    seen_visual: set[str] = set()
    for link in robot.links:
        for shape in link.shapes:
            geometry = shape.geometry
            if geometry.kind == "mesh":
                geometry.path = _resolve_existing(
                    robot, _line(shape), geometry.uri or "", base_dir, packages
                )
                reads.append((geometry.uri or "", Path(geometry.path), _line(shape)))
                if prebuilt is not None:
                    found = prebuilt_mesh(prebuilt, geometry.path)
                    if found is not None and str(found) != geometry.path:
                        visual = shape.role == "visual"
                        if str(found) not in originals or (
                            visual and str(found) not in seen_visual
                        ):
                            originals[str(found)] = geometry.path
                        if visual:
                            seen_visual.add(str(found))
                        geometry.path = str(found)
                if mesh_format(geometry.path) is None:
                    raise InputError(
                        f"mesh '{geometry.uri}' has an unsupported format",
                        file=robot.source,
                        line=_line(shape),
                        hint=f"mjcfbuild reads {', '.join(sorted(MESH_FORMATS))}",
                    )
                mesh_paths.append(geometry.path)
            if shape.material is not None and shape.material.texture:
                uri = shape.material.texture
                # at the shape's line: a texture is named in its <material>, not its geometry
                shape.material.texture = _resolve_existing(
                    robot, shape.line, uri, base_dir, packages
                )
                reads.append((uri, Path(shape.material.texture), shape.line))
    if roots is not None:
        far = reads_outside(reads, packages, roots)
        _warn_outside(robot, far)
        if outside is not None:
            outside.extend(far)
    ids = assign_mesh_ids(mesh_paths)
    for link in robot.links:
        for shape in link.shapes:
            if shape.geometry.kind == "mesh":
                assert shape.geometry.path is not None, "every mesh was resolved above"
                shape.geometry.mesh_id = ids[shape.geometry.path]
    return originals


class OutsideRead(NamedTuple):
    """A file the description reads from outside every folder it may read from."""

    uri: str  # as the description writes it
    path: Path  # the file it names
    line: int | None  # the URDF line that names it


def reads_outside(
    reads: Sequence[tuple[str, Path, int | None]],
    packages: PackageResolver,
    roots: Sequence[Path],
) -> list[OutsideRead]:
    """The files of ``reads`` (URI, path, line) outside ``roots`` and every package folder
    (those the URIs name, and any folder with a package.xml), the first read of each URI.

    Paths are compared as written (``..`` removed, links kept): a package installed with
    links into its sources (colcon --symlink-install) is still inside its folder.
    """
    inside = [normalise(root) for root in roots]
    inside += filter(None, (uri_package_folder(uri, packages) for uri, _, _ in reads))
    found: dict[str, OutsideRead] = {}
    for uri, path, line in reads:
        if uri in found or any(path == root or root in path.parents for root in inside):
            continue
        enclosing = find_enclosing_package(path)  # a ROS package found by no URI
        if enclosing is not None:
            inside.append(enclosing[1])
            continue
        found[uri] = OutsideRead(uri, path, line)
    return list(found.values())


def _warn_outside(robot: Robot, outside: Sequence[OutsideRead]) -> None:
    """Warn once per URI about a file read from outside (``reads_outside``)."""
    for uri, path, line in outside:
        where = f"{robot.source}:{line}" if line is not None else robot.source
        # The path quoted: warnings that differ only in quoted parts print as one line.
        read = "" if uri.strip() == str(path) else f" ('{path}')"
        robot.warnings.append(
            f"{where}: '{uri}'{read} is outside every package folder and robot.yaml's folder, "
            "and the model publishes it; move the file into the description, or set "
            "source.read_outside: true if it is meant"
        )


def _resolve_existing(
    robot: Robot, line: int | None, uri: str, base_dir: Path, packages: PackageResolver
) -> str:
    """The path ``uri`` names (at ``line`` of the URDF), or an error saying why there is
    none."""
    try:
        path = resolve_uri(uri, base_dir, packages)
    except InputError as exc:
        raise InputError(exc.message, file=robot.source, line=line, hint=exc.hint) from None
    problem = unreadable_file(path)
    match = case_match(path) if problem and problem.startswith("not found") else None
    looked = _looked_at(uri, path)
    if match is not None:
        raise InputError(
            f"file '{uri}' not found; did you mean '{_respelt(uri, path, match)}'?{looked}",
            file=robot.source,
            line=line,
            hint="write the name as the file is spelt: letter case matters here",
        )
    if problem and problem.startswith("not found") and _from_elsewhere(uri):
        raise InputError(
            f"file '{uri}' not found: an absolute path, likely written on another machine",
            file=robot.source,
            line=line,
            hint="make it relative to the URDF's folder, or a package:// URI",
        )
    if problem:
        raise InputError(
            f"file '{uri}' {problem}{looked}",
            file=robot.source,
            line=line,
            hint="check the path and the 'packages' in robot.yaml",
        )
    return str(path)


def _line(shape: Shape) -> int | None:
    """Where a shape's mesh file is named: its <mesh> element's line, else the shape's."""
    return shape.geometry.line or shape.line


def _from_elsewhere(uri: str) -> bool:
    """Whether ``uri`` is a plain absolute path whose folder is not on this machine either
    (``/home/someone/ws/src/...``): written where the description was made, not here."""
    written = uri.strip()
    return os.path.isabs(written) and not os.path.isdir(os.path.dirname(written))


def _looked_at(uri: str, path: Path) -> str:
    """`` (looked at PATH)``: where a URI that names a package (``package://``, ``file://``,
    ``$(find)``) was looked for; nothing for a plain path, which the message already shows
    as written (relative to the URDF, or absolute)."""
    if "://" not in uri or os.path.normpath(uri.strip()) == str(path):
        return ""
    return f" (looked at {path})"


def _respelt(uri: str, path: Path, match: Path) -> str:
    """``uri`` with the parts that differ from ``match`` in letter case spelt as ``match``
    spells them; the file's path where the URI does not end with those parts as written."""
    tail = case_suggestion(path, match).split("/")
    parts = uri.split("/")
    written = parts[-len(tail) :]
    if len(parts) >= len(tail) and [p.casefold() for p in written] == [t.casefold() for t in tail]:
        return "/".join(parts[: -len(tail)] + tail)
    return str(match)
