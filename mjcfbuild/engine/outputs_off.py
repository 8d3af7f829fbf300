"""The files of an output robot.yaml no longer asks for: the exported URDF and its meshes
(``output.urdf`` off, or renamed), the package (``output.package`` off).

Turning such an output off left its files in the output folder: a copy of the model that no
build kept current, which ``build`` and ``check --up-to-date`` called up to date. As the
training variant's files go when ``output.training`` is off
(:mod:`mjcfbuild.engine.training_files`), a build now removes them before its tasks run. What
is removed is what the output's own record (its task's file in the state folder) says it
wrote, and only where the record of written files (:mod:`mjcfbuild.engine.written`) says a
build wrote those very bytes: as ``clean`` decides, a file the user put there or edited since
stays, and is named, and so does the package's changelog (the history of earlier builds, which
no build can write again).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.outputs import (
    PACKAGE_CHANGELOG,
    PACKAGE_COPIES,
    PACKAGE_FOLDER,
    URDF_EXPORT_RECORD,
)

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext
    from mjcfbuild.graph.context import GraphContext


@dataclass
class Leftover:
    """The files of one output robot.yaml no longer asks for (or asks for elsewhere)."""

    key: str  # the robot.yaml setting: ``output.urdf``
    why: str  # ``is off``, ``names another file``
    removable: list[Path] = field(default_factory=list)  # the build's, as it wrote them
    kept: list[Path] = field(default_factory=list)  # edited since a build wrote them
    history: list[Path] = field(default_factory=list)  # the package's changelog
    yours: list[Path] = field(default_factory=list)  # no build wrote them
    records: list[Path] = field(default_factory=list)  # the output's records, which go too


def leftovers(ctx: BuildContext) -> list[Leftover]:
    """The outputs whose files an earlier build wrote and this one will not write; only
    those with something left to remove or say."""
    found = [_export(ctx), _package(ctx)]
    return [item for item in found if item is not None and (item.removable or item.records)]


def remove_leftovers(ctx: BuildContext) -> list[Leftover]:
    """Remove the files of :func:`leftovers` a build wrote (and their records), then the
    folders left empty; what each output left, as it was before the removal."""
    found = leftovers(ctx)
    for item in found:
        for path in item.removable:
            path.unlink(missing_ok=True)
        for record in item.records:
            record.unlink(missing_ok=True)
        for folder in sorted({p.parent for p in item.removable}, key=_depth, reverse=True):
            _remove_empty(folder, ctx.out_dir)
    return found


def _export(ctx: BuildContext) -> Leftover | None:
    """The exported URDF and its meshes an earlier build wrote, where ``output.urdf`` is off
    now or names another file or mesh folder."""
    record = ctx.state(URDF_EXPORT_RECORD)
    data = _read(record)
    if data is None or not isinstance(data.get("urdf"), str):
        return None  # none, or from an mjcfbuild that did not record the names
    old_urdf = ctx.out_dir / data["urdf"]
    old_meshes = ctx.out_dir / str(data.get("mesh_folder", ""))
    meshes = [name for name in data.get("meshes", []) if isinstance(name, str)]
    if ctx.urdf_path is None:
        item = Leftover("output.urdf", "is off", records=[record])
        names = [old_urdf, *(old_meshes / name for name in meshes)]
    else:
        item = Leftover("output.urdf", "names another file")
        names = [old_urdf] if old_urdf != ctx.urdf_path else []
        if old_meshes != ctx.urdf_mesh_dir:
            names += [old_meshes / name for name in meshes]
    # Never one this build writes: a mesh folder that is the model's assets/, say.
    keep = {ctx.robot_path, ctx.scene_path, ctx.urdf_path}
    _sort(ctx, item, [path for path in names if path not in keep and not _in_assets(ctx, path)])
    return item


def _sources(ctx: BuildContext) -> set[Path]:
    """The files this build reads as robot.yaml names them: its source and its parts' (an
    exported URDF robot.yaml now builds from is no leftover, though no output writes it)."""
    found = {Path(os.path.normpath(ctx.source_path))} if ctx.source_kind != "description" else set()
    for part in ctx.manifest.attach:
        found.add(Path(os.path.normpath(ctx.resolve(part.source.file))))
    return found


def _through_link(ctx: BuildContext, path: Path) -> bool:
    """Whether ``path`` lies in a linked folder below the output folder (a package folder
    linked to a checkout of the user's): nothing is removed through a link."""
    return any(folder.is_symlink() for folder in path.parents if ctx.out_dir in folder.parents)


def _package(ctx: BuildContext) -> Leftover | None:
    """The package folder's files an earlier build wrote, where ``output.package`` is off."""
    copies = ctx.state(PACKAGE_COPIES)
    data = _read(copies)
    if ctx.manifest.output.package or data is None:
        return None
    folder = ctx.out_dir / PACKAGE_FOLDER
    names = [folder / name for name in data.get("files", []) if isinstance(name, str)]
    item = Leftover("output.package", "is off", records=[copies])
    _sort(ctx, item, [*names, folder / PACKAGE_CHANGELOG])
    if folder.is_dir() and not folder.is_symlink():
        listed = {*item.removable, *item.kept, *item.history}
        found = []
        for root, _, files in os.walk(folder):  # os.walk does not enter linked folders
            found += [Path(root) / name for name in files]
        item.yours = sorted(path for path in found if path not in listed)
    return item


def _sort(ctx: BuildContext, item: Leftover, paths: list[Path]) -> None:
    """Place each of ``paths`` (files the output's record names) in ``item``: the build's to
    remove, edited since, the changelog; a file that is not there, or that no build recorded
    writing (the user's), is not the build's to remove."""
    from mjcfbuild.engine.written import edited, recorded, written_file

    record = recorded(ctx) or {}
    sources = _sources(ctx)
    for path in dict.fromkeys(paths):
        if Path(os.path.normpath(path)) in sources or _through_link(ctx, path):
            continue
        name = _name(ctx, path)
        if name is None or name not in record or not written_file(ctx.out_dir, name):
            continue
        if edited(ctx.out_dir, name, record[name]):
            item.kept.append(path)
        elif name == f"{PACKAGE_FOLDER}/{PACKAGE_CHANGELOG}":
            item.history.append(path)
        else:
            item.removable.append(path)


def _name(ctx: BuildContext, path: Path) -> str | None:
    """``path`` relative to the output folder (posix); None above it or in its state."""
    relative = os.path.relpath(os.path.normpath(path), ctx.out_dir)
    parts = Path(relative).parts
    if not parts or parts[0] in (".", "..", ctx.state_dir.name) or os.path.isabs(relative):
        return None
    return "/".join(parts)


def _in_assets(ctx: BuildContext, path: Path) -> bool:
    return ctx.assets_dir == path or ctx.assets_dir in path.parents


def _read(path: Path) -> dict | None:
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) else None


def _depth(path: Path) -> int:
    return len(path.parts)


def _remove_empty(folder: Path, stop: Path) -> None:
    """Remove ``folder`` and the folders above it, up to ``stop`` (not included), while they
    are empty; never through a link."""
    while folder != stop and stop in folder.parents and folder.is_dir():
        if folder.is_symlink() or any(folder.iterdir()):
            return
        folder.rmdir()
        folder = folder.parent


def say(ctx: BuildContext, item: Leftover) -> str:
    """The line saying what the build removed of ``item`` and what it kept there."""
    line = f"{item.key} {item.why}"
    if item.removable:
        line = f"removed {', '.join(grouped_files(ctx, item.removable))}: {line}"
    kept = [f"{ctx.label(path)} (edited since a build wrote it)" for path in item.kept]
    kept += [
        f"{ctx.label(path)} (the history of earlier builds: no build can write it again; "
        "remove it yourself if it is to go)"
        for path in item.history
    ]
    if item.yours:
        shown = ", ".join(ctx.label(path) for path in item.yours[:5])
        more = f" and {len(item.yours) - 5} more" if len(item.yours) > 5 else ""
        kept.append(f"{shown}{more} (not written by a build)")
    return line + (f"; kept {', '.join(kept)}" if kept else "")


def grouped_files(ctx: GraphContext, files: list[Path]) -> list[str]:
    """Removed files as a message lists them: files at the top of the output folder by name,
    the others counted by the top folder they were in: ``mjcf/package/ (9 files)`` for a
    folder that went with them, ``2 files in mjcf/package/`` for one that stays (``clean``
    and a build removing an output turned off say it alike)."""
    top: list[str] = []
    counts: dict[Path, int] = {}
    for path in files:
        relative = path.relative_to(ctx.out_dir)
        if len(relative.parts) == 1:
            top.append(ctx.label(path))
        else:
            folder = ctx.out_dir / relative.parts[0]
            counts[folder] = counts.get(folder, 0) + 1
    for folder, n in counts.items():
        label, many = ctx.label(folder) + "/", f"{n} file{'s' if n > 1 else ''}"
        top.append(f"{many} in {label}" if folder.is_dir() else f"{label} ({many})")
    return top


def stale_lines(ctx: BuildContext) -> list[str]:
    """``check --up-to-date``'s lines for the files of outputs robot.yaml no longer asks for,
    which the next build removes."""
    lines = []
    for item in leftovers(ctx):
        if item.removable:
            files = ", ".join(ctx.label(path) for path in item.removable[:3])
            more = f" and {len(item.removable) - 3} more" if len(item.removable) > 3 else ""
            lines.append(f"{files}{more}: no longer built ({item.key} {item.why})")
    return lines
