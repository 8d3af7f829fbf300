"""Compiling a built model quickly in a process that has compiled it before.

MuJoCo keeps the meshes it has processed in a cache in each process, by file name and time:
a second compile of a model skips the parsing, normals and bounding volumes that make a
first one slow (go1's 13 MB trunk: 0.85 s the first time, 0.12 s after). A build's steps
read the mesh files under the names of their products in the build's state folder, and the
published model names its copies in ``assets/``. So the check and the previews compile the
published model reading each asset from the product it was published from, wherever the two
files hold the same bytes (from the product's binary copy where it has one, which compiles
to the same model: mjcfbuild.meshes.mshfile): MuJoCo reads what the published model names,
and the worker that assembled the model (or was warmed for it, :func:`warm_meshes`) finds it
cached. An asset edited after the build is read from the published file, as is everything
else.
"""

from __future__ import annotations

import contextlib
import filecmp
import hashlib
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

# The assembly report's key for {asset file name: its product file, relative to the report}.
SOURCES_KEY = "asset_sources"
# ... and for {asset file name: [the product's binary copy, its MD5]} (mjcfbuild.meshes.mshfile).
COPIES_KEY = "asset_copies"


@dataclass(frozen=True)
class AssetSource:
    """Where a published asset came from: its product file, and the product's binary copy of
    it with the copy's MD5 where the product has one (what compiles read instead)."""

    product: Path
    copy: Path | None = None
    copy_md5: str | None = None

    @property
    def read(self) -> Path:
        """The file this build's compiles read for the asset."""
        return self.copy or self.product


def source_entries(assets: dict[str, str], report_dir: Path) -> dict[str, str]:
    """The report's record of where each asset was published from (``assets``: name to
    product path), relative to the report's folder so the record is the same in any folder."""
    return {name: os.path.relpath(path, report_dir) for name, path in sorted(assets.items())}


def copy_entries(copies: dict[str, tuple[str, str]], report_dir: Path) -> dict[str, list[str]]:
    """The report's record of the binary copies compiles read (``copies``: asset name to the
    copy's path and MD5), relative to the report's folder."""
    return {
        name: [os.path.relpath(path, report_dir), md5]
        for name, (path, md5) in sorted(copies.items())
    }


def asset_sources(report: Path | None) -> dict[str, AssetSource]:
    """Where the assets of a built model were published from, by asset file name; empty when
    the build's assembly report is missing or older than the record."""
    if report is None:
        return {}
    try:
        record = json.loads(report.read_text())
        entries = record.get(SOURCES_KEY) or {}
        copies = record.get(COPIES_KEY) or {}
    except (OSError, ValueError, AttributeError):
        return {}
    sources = {}
    for name, path in entries.items():
        copy = copies.get(name)
        if isinstance(copy, list) and len(copy) == 2:
            sources[name] = AssetSource(report.parent / path, report.parent / copy[0], copy[1])
        else:
            sources[name] = AssetSource(report.parent / path)
    return sources


def compile_model(path: Path, sources: dict[str, AssetSource] | None = None) -> Any:
    """The MjModel of the MJCF file at ``path``, read as :func:`spec_reading_sources` says.

    Raises what MuJoCo raises for a model that does not load.
    """
    import mujoco

    if not sources:
        return mujoco.MjModel.from_xml_path(str(path))
    return spec_reading_sources(path, sources).compile()


def spec_reading_sources(path: Path, sources: dict[str, AssetSource]) -> Any:
    """The MjSpec of the MJCF file at ``path``, each mesh and texture that is byte-identical
    to its product in ``sources`` (by asset file name) read from the product's binary copy
    where it has one unchanged, else from the product."""
    import mujoco

    spec = mujoco.MjSpec.from_file(str(path))
    base = Path(spec.modelfiledir)
    for assets, folder in ((spec.meshes, spec.meshdir), (spec.textures, spec.texturedir)):
        for asset in assets:
            if not asset.file:
                continue
            published = base / folder / asset.file
            source = sources.get(Path(asset.file).name)
            if source is not None and _same_bytes(published, source.product):
                asset.file = str(_intact_copy(source) or source.product)
    return spec


def _intact_copy(source: AssetSource) -> Path | None:
    """The product's binary copy, if it holds what the build wrote (the copy and the product
    are separate files: a conversion stopped between them leaves one of them older)."""
    if source.copy is None or source.copy_md5 is None:
        return None
    try:
        data = source.copy.read_bytes()
    except OSError:
        return None
    return (
        source.copy
        if hashlib.md5(data, usedforsecurity=False).hexdigest() == source.copy_md5
        else None
    )


def warm_meshes(files: list[str]) -> None:
    """Have MuJoCo process the mesh files ``files`` into this process's cache, as the model's
    compiles will: with a convex hull where a collision geom uses the file.

    MuJoCo keeps the first processing of a file, and one without a hull does not serve a
    compile that needs it: that compile processes the file again, every time, without
    caching it (measured: g1's assembly took 1.9 s instead of 0.4 in a worker that had
    warmed its meshes without hulls). Hulls of meshes only drawn would be work for nothing."""
    import mujoco

    from mjcfbuild.meshes.mshfile import SUFFIX

    listed = set(files)
    meshes = [
        f
        for f in files
        if Path(f).suffix.lower() in (".obj", ".stl", SUFFIX)
        # an OBJ file beside its binary copy: compiles read the copy (meshes.mshfile)
        and (Path(f).suffix == SUFFIX or str(Path(f).with_suffix(SUFFIX)) not in listed)
    ]
    if not meshes:
        return
    colliding = collision_files(meshes)
    spec = mujoco.MjSpec()
    for index, file in enumerate(meshes):
        spec.add_mesh(name=f"m{index}", file=file)
        if file in colliding:
            spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"m{index}")
    with contextlib.suppress(ValueError):  # a mesh MuJoCo rejects: the model's steps say why
        spec.compile()


def collision_files(files: list[str]) -> set[str]:
    """Which of the product files ``files`` collision geoms use: the parts of a
    decomposition, and a mesh product's collision mesh and hull and their binary copies (its
    summary, beside its folder, names them)."""
    from mjcfbuild.meshes.mshfile import copy_name
    from mjcfbuild.meshes.product import read_product

    colliding = set()
    summaries: dict[Path, set[str]] = {}
    for file in files:
        folder = Path(file).parent
        if folder.parent.name == "decompositions":
            colliding.add(file)
            continue
        if folder not in summaries:
            try:
                product = read_product(folder.with_suffix(".json"))
                used = [name for name in (product.collision, product.hull) if name]
                summaries[folder] = {*used, *(copy_name(name) for name in used)}
            except (OSError, ValueError, KeyError, TypeError):
                summaries[folder] = set()
        if Path(file).name in summaries[folder]:
            colliding.add(file)
    return colliding


def _same_bytes(published: Path, source: Path) -> bool:
    try:
        return filecmp.cmp(published, source, shallow=False)
    except OSError:
        return False
