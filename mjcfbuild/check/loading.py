"""Compiling a built model quickly in a process that has compiled it before.

MuJoCo keeps the meshes it has processed in a cache in each process, by file name and time:
a second compile of a model skips the parsing, normals and bounding volumes that make a
first one slow (go1's 13 MB trunk: 0.85 s the first time, 0.12 s after). A build's steps
read the mesh files under the names of their products in the build's state folder, and the
published model names its copies in ``assets/``. So the check and the previews compile the
published model reading each asset from the product it was published from, wherever the two
files hold the same bytes: MuJoCo reads exactly what the published model names, and the
worker that assembled the model (or was warmed for it, :func:`warm_meshes`) finds it cached.
An asset edited after the build is read from the published file, as is everything else.
"""

from __future__ import annotations

import contextlib
import filecmp
import json
import os
from pathlib import Path
from typing import Any

# The assembly report's key for {asset file name: its product file, relative to the report}.
SOURCES_KEY = "asset_sources"


def source_entries(assets: dict[str, str], report_dir: Path) -> dict[str, str]:
    """The report's record of where each asset was published from (``assets``: name to
    product path), relative to the report's folder so the record is the same in any folder."""
    return {name: os.path.relpath(path, report_dir) for name, path in sorted(assets.items())}


def asset_sources(report: Path | None) -> dict[str, Path]:
    """The products the assets of a built model were published from, by asset file name;
    empty when the build's assembly report is missing or older than the record."""
    if report is None:
        return {}
    try:
        entries = json.loads(report.read_text()).get(SOURCES_KEY) or {}
    except (OSError, ValueError, AttributeError):
        return {}
    return {name: report.parent / path for name, path in entries.items()}


def compile_model(path: Path, sources: dict[str, Path] | None = None) -> Any:
    """The MjModel of the MJCF file at ``path``, read as :func:`spec_reading_sources` says.

    Raises what MuJoCo raises for a model that does not load.
    """
    import mujoco

    if not sources:
        return mujoco.MjModel.from_xml_path(str(path))
    return spec_reading_sources(path, sources).compile()


def spec_reading_sources(path: Path, sources: dict[str, Path]) -> Any:
    """The MjSpec of the MJCF file at ``path``, each mesh and texture that is byte-identical
    to its entry in ``sources`` (asset file name to product file) read from that entry."""
    import mujoco

    spec = mujoco.MjSpec.from_file(str(path))
    base = Path(spec.modelfiledir)
    for assets, folder in ((spec.meshes, spec.meshdir), (spec.textures, spec.texturedir)):
        for asset in assets:
            if not asset.file:
                continue
            published = base / folder / asset.file
            source = sources.get(Path(asset.file).name)
            if source is not None and _same_bytes(published, source):
                asset.file = str(source)
    return spec


def warm_meshes(files: list[str]) -> None:
    """Have MuJoCo process the mesh files ``files`` into this process's cache, as the model's
    compiles will: with a convex hull where a collision geom uses the file.

    MuJoCo keeps the first processing of a file, and one without a hull does not serve a
    compile that needs it: that compile processes the file again, every time, without
    caching it (measured: g1's assembly took 1.9 s instead of 0.4 in a worker that had
    warmed its meshes without hulls). Hulls of meshes only drawn would be work for nothing."""
    import mujoco

    meshes = [f for f in files if Path(f).suffix.lower() in (".obj", ".stl", ".msh")]
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
    decomposition, and a mesh product's collision mesh and hull (its summary, beside its
    folder, names them)."""
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
                summaries[folder] = {name for name in (product.collision, product.hull) if name}
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
