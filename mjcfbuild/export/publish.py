"""Writing an export to disk: the URDF and its mesh files, atomically, nothing outside them."""

from __future__ import annotations

import os
from pathlib import Path

from mjcfbuild.errors import OutputError
from mjcfbuild.export.stamp import refuse_overwriting
from mjcfbuild.export.urdf_writer import ExportResult
from mjcfbuild.fsutil import write_if_changed


def default_asset_prefix(urdf_path: Path, mesh_dir: Path) -> str:
    """How the URDF refers to ``mesh_dir``: a relative path from the URDF's folder."""
    relative = os.path.relpath(mesh_dir, urdf_path.parent)
    return "" if relative == "." else relative.replace(os.sep, "/") + "/"


def publish(
    result: ExportResult, urdf_path: Path, mesh_dir: Path, force: bool = False
) -> dict[str, bytes]:
    """Write the mesh files, then the URDF (last, so a URDF never names missing files).
    Unless ``force``, nothing is written where a file export-urdf did not write would be
    replaced by other bytes (:func:`~mjcfbuild.export.stamp.refuse_overwriting`).

    Returns every written file's bytes by path. Mesh file names come from
    :func:`~mjcfbuild.export.meshfiles.safe_stem`, so they never leave ``mesh_dir``.
    """
    if not force:
        files = {mesh_dir / name: data for name, data in result.meshes.items()}
        refuse_overwriting([urdf_path, *sorted(files)], files)
    written: dict[str, bytes] = {}
    try:
        if result.meshes:
            mesh_dir.mkdir(parents=True, exist_ok=True)
        for name, data in sorted(result.meshes.items()):
            path = mesh_dir / name
            if path.parent != mesh_dir:  # names are made safe; this guards against a bug
                raise OutputError(f"mesh file name '{name}' leaves the mesh folder")
            write_if_changed(path, data)
            written[str(path)] = data
        urdf_path.parent.mkdir(parents=True, exist_ok=True)
        write_if_changed(urdf_path, result.urdf)
    except OSError as exc:
        raise _unwritable(exc, urdf_path) from None
    written[str(urdf_path)] = result.urdf
    return written


def _unwritable(exc: OSError, urdf_path: Path) -> OutputError:
    """The one-line error of a file or folder of the export that cannot be written. A folder
    that cannot be made where nothing says it is missing (``/proc/m``: a file system that
    refuses new folders) is said so, rather than as the system's "no such file"."""
    from mjcfbuild.errors import write_failure

    name = exc.filename or urdf_path
    if isinstance(exc, FileNotFoundError):
        why = "cannot create it there (that file system, or a folder above it, refuses it)"
    else:
        known = write_failure(exc, name)
        why = known.message if known is not None else f"cannot write: {exc.strerror or exc}"
    return OutputError(
        f"cannot write the URDF export: {why.removeprefix('cannot write: ')}",
        file=name,
        hint="choose another -o or --mesh-folder",
    )
