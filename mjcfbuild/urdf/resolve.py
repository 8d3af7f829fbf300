"""Resolving every file a parsed URDF refers to, and naming its meshes."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import case_match, case_suggestion, unreadable_file
from mjcfbuild.meshes.formats import MESH_FORMATS, mesh_format
from mjcfbuild.meshes.naming import assign_mesh_ids
from mjcfbuild.meshes.prebuilt import prebuilt_mesh
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.sources.uris import resolve_uri
from mjcfbuild.urdf.model import Robot, Shape


def resolve_files(
    robot: Robot, base_dir: Path, packages: PackageResolver, prebuilt: Path | None = None
) -> None:
    """Fill in the real path of every mesh and texture, and give each mesh file an id.

    Relative references are relative to ``base_dir``, the folder of the URDF or xacro file.
    A reference that cannot be resolved, a missing file or an unsupported format is an
    :class:`InputError` at the line of the element that names it. With ``prebuilt``, a
    folder of meshes converted before, a mesh with a pre-generated OBJ there is read from it.
    """
    mesh_paths: list[str] = []
    for link in robot.links:
        for shape in link.shapes:
            geometry = shape.geometry
            if geometry.kind == "mesh":
                geometry.path = _resolve_existing(
                    robot, shape, geometry.uri or "", base_dir, packages
                )
                if prebuilt is not None:
                    found = prebuilt_mesh(prebuilt, geometry.path)
                    geometry.path = str(found) if found is not None else geometry.path
                if mesh_format(geometry.path) is None:
                    raise InputError(
                        f"mesh '{geometry.uri}' has an unsupported format",
                        file=robot.source,
                        line=shape.line,
                        hint=f"mjcfbuild reads {', '.join(sorted(MESH_FORMATS))}",
                    )
                mesh_paths.append(geometry.path)
            if shape.material is not None and shape.material.texture:
                shape.material.texture = _resolve_existing(
                    robot, shape, shape.material.texture, base_dir, packages
                )
    ids = assign_mesh_ids(mesh_paths)
    for link in robot.links:
        for shape in link.shapes:
            if shape.geometry.kind == "mesh":
                assert shape.geometry.path is not None, "every mesh was resolved above"
                shape.geometry.mesh_id = ids[shape.geometry.path]


def _resolve_existing(
    robot: Robot, shape: Shape, uri: str, base_dir: Path, packages: PackageResolver
) -> str:
    try:
        path = resolve_uri(uri, base_dir, packages)
    except InputError as exc:
        raise InputError(exc.message, file=robot.source, line=shape.line, hint=exc.hint) from None
    problem = unreadable_file(path)
    match = case_match(path) if problem and problem.startswith("not found") else None
    if match is not None:
        raise InputError(
            f"file '{uri}' not found; did you mean '{_respelt(uri, path, match)}'? "
            f"(looked at {path})",
            file=robot.source,
            line=shape.line,
            hint="write the name as the file is spelt: letter case matters here",
        )
    if problem:
        raise InputError(
            f"file '{uri}' {problem} (looked at {path})",
            file=robot.source,
            line=shape.line,
            hint="check the path and the 'packages' in robot.yaml",
        )
    return str(path)


def _respelt(uri: str, path: Path, match: Path) -> str:
    """``uri`` with the parts that differ from ``match`` in letter case spelt as ``match``
    spells them; the file's path where the URI does not end with those parts as written."""
    tail = case_suggestion(path, match).split("/")
    parts = uri.split("/")
    written = parts[-len(tail) :]
    if len(parts) >= len(tail) and [p.casefold() for p in written] == [t.casefold() for t in tail]:
        return "/".join(parts[: -len(tail)] + tail)
    return str(match)
