"""Resolving every file a parsed URDF refers to, and naming its meshes."""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import case_match, case_suggestion, normalise, unreadable_file
from mjcfbuild.meshes.formats import MESH_FORMATS, mesh_format
from mjcfbuild.meshes.naming import assign_mesh_ids
from mjcfbuild.meshes.prebuilt import prebuilt_mesh
from mjcfbuild.numbers import exact_list
from mjcfbuild.sources.packages import PackageResolver, find_enclosing_package
from mjcfbuild.sources.uris import resolve_uri, uri_package_folder
from mjcfbuild.urdf.model import Robot, Shape


@dataclass
class ResolvedFiles:
    """What resolving a URDF's files found besides the paths it filled in."""

    # the mesh file each pre-generated OBJ stands for (convert -a), whose look it takes
    originals: dict[str, str] = field(default_factory=dict)
    textures: list[str] = field(default_factory=list)  # the material textures found
    missing: list[str] = field(default_factory=list)  # the textures looked for and not found


def resolve_files(
    robot: Robot,
    base_dir: Path,
    packages: PackageResolver,
    prebuilt: Path | None = None,
    roots: Sequence[Path] | None = None,
    outside: list[OutsideRead] | None = None,
) -> ResolvedFiles:
    """Fill in the real path of every mesh and texture, and give each mesh file an id.

    Relative references are relative to ``base_dir``, the folder of the URDF or xacro file.
    A reference that cannot be resolved, a missing file or an unsupported format is an
    :class:`InputError` at the line of the element that names it. With ``prebuilt``, a
    folder of meshes converted before, a mesh with a pre-generated OBJ there is read from it.
    With ``roots`` (the folders the description may read: robot.yaml's, its packages'), a
    file outside them and outside every package a URI names gets a warning in
    ``robot.warnings``, once per URI, and is added to ``outside`` where given. A material
    texture that is not there is a warning in ``robot.warnings`` at its ``<texture>``, and the
    material keeps only its colour. Returns the mesh file each pre-generated OBJ stands for (a
    visual's where several do), whose look it takes where it has none of its own, and the
    textures found and looked for in vain.
    """
    reads: list[tuple[str, Path, int | None]] = []
    textures: list[str] = []
    missing: list[str] = []
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
                read = _resolve_texture(robot, shape, base_dir, packages, missing)
                if read is not None:
                    reads.append(read)
                    textures.append(str(read[1]))
    if roots is not None:
        far = reads_outside(reads, packages, roots)
        _warn_outside(robot, far, base_dir)
        if outside is not None:
            outside.extend(far)
    ids = assign_mesh_ids(mesh_paths)
    for link in robot.links:
        for shape in link.shapes:
            if shape.geometry.kind == "mesh":
                assert shape.geometry.path is not None, "every mesh was resolved above"
                shape.geometry.mesh_id = ids[shape.geometry.path]
    return ResolvedFiles(originals, sorted(set(textures)), sorted(set(missing)))


def _resolve_texture(
    robot: Robot,
    shape: Shape,
    base_dir: Path,
    packages: PackageResolver,
    missing: list[str],
) -> tuple[str, Path, int | None] | None:
    """Resolve the texture of ``shape``'s material in place: (its URI, path, line) where
    the file is there; else None, the texture dropped, one warning per ``<texture>`` (a
    material shared by name is resolved once) and the path it looked at in ``missing``.

    A missing texture is no error: urdfdom and MuJoCo's URDF import take the description,
    and the model draws the material's colour.
    """
    material = shape.material
    assert material is not None and material.texture, "a shape with a texture"
    uri = material.texture
    # At the shape's line where the <texture>'s own is unknown (a URDF parsed before it was
    # recorded): a texture is named in its <material>, not its geometry.
    line = material.texture_line or shape.line
    path, problem = _look_up(uri, base_dir, packages, relative=True)
    if problem is None:
        assert path is not None, "a path or a problem"
        material.texture = str(path)
        return uri, path, line
    material.texture = None
    message, hint = problem
    if path is not None:
        missing.append(str(path))
    else:  # the URI names no path (an unknown package), and the message not the URI
        message = f"'{uri}': {message}"
    where = f"{robot.source}:{line}" if line is not None else robot.source
    named = f"material '{material.name}': " if material.name else ""
    colour = (
        f"the material's colour, rgba {exact_list(material.rgba)}"
        if material.rgba is not None
        else "MuJoCo's default grey"
    )
    fix = f"{hint}, or remove the <texture>" if hint else "remove the <texture>"
    robot.warnings.append(f"{where}: {named}texture {message}; the model draws {colour} ({fix})")
    return None


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


def _warn_outside(robot: Robot, outside: Sequence[OutsideRead], base_dir: Path) -> None:
    """Warn once per URI about a file read from outside (``reads_outside``), its path named
    from ``base_dir`` (the URDF's folder): the report keeps the warning, the same bytes in
    any folder."""
    for uri, path, line in outside:
        where = f"{robot.source}:{line}" if line is not None else robot.source
        shown = Path(os.path.relpath(path, base_dir)).as_posix()
        # The path quoted: warnings that differ only in quoted parts print as one line.
        read = "" if os.path.normpath(uri.strip()) in (str(path), shown) else f" ('{shown}')"
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
    path, problem = _look_up(uri, base_dir, packages)
    if problem is not None:
        message, hint = problem
        raise InputError(message, file=robot.source, line=line, hint=hint)
    assert path is not None, "a path or a problem"
    return str(path)


def _look_up(
    uri: str, base_dir: Path, packages: PackageResolver, relative: bool = False
) -> tuple[Path | None, tuple[str, str | None] | None]:
    """The path ``uri`` names and, where it names no readable file, why (a message and a
    hint); the path is None where the URI names none (an unknown package). With
    ``relative``, the message names the path from ``base_dir`` (for a warning, which the
    report keeps: the same bytes in any folder), else as it is."""
    try:
        path = resolve_uri(uri, base_dir, packages)
    except InputError as exc:
        return None, (exc.message, exc.hint)
    problem = unreadable_file(path)
    if not problem:
        return path, None
    match = case_match(path) if problem.startswith("not found") else None
    looked = _looked_at(uri, path, base_dir if relative else None)
    if match is not None:
        return path, (
            f"file '{uri}' not found; did you mean '{_respelt(uri, path, match)}'?{looked}",
            "write the name as the file is spelt: letter case matters here",
        )
    if problem.startswith("not found") and _from_elsewhere(uri):
        return path, (
            f"file '{uri}' not found: an absolute path, likely written on another machine",
            "make it relative to the URDF's folder, or a package:// URI",
        )
    return path, (
        f"file '{uri}' {problem}{looked}",
        "check the path and the 'packages' in robot.yaml",
    )


def _line(shape: Shape) -> int | None:
    """Where a shape's mesh file is named: its <mesh> element's line, else the shape's."""
    return shape.geometry.line or shape.line


def _from_elsewhere(uri: str) -> bool:
    """Whether ``uri`` is a plain absolute path whose folder is not on this machine either
    (``/home/someone/ws/src/...``): written where the description was made, not here."""
    written = uri.strip()
    return os.path.isabs(written) and not os.path.isdir(os.path.dirname(written))


def _looked_at(uri: str, path: Path, base_dir: Path | None = None) -> str:
    """`` (looked at PATH)``: where a URI that names a package (``package://``, ``file://``,
    ``$(find)``) was looked for, named from ``base_dir`` (the URDF's folder) where given;
    nothing for a plain path, which the message already shows as written (relative to the
    URDF, or absolute)."""
    if "://" not in uri or os.path.normpath(uri.strip()) == str(path):
        return ""
    if base_dir is not None:
        shown = Path(os.path.relpath(path, base_dir)).as_posix()
        return f" (looked at {shown}, from the URDF's folder)"
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
