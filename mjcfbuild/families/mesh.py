"""The ``mesh`` family: one task per mesh file, converting it into the products the model uses
(OBJ parts, a collision mesh, a hull); products are shared through the cache."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.graph.family import (
    Family,
    discovered_inputs,
    file_task,
    largest_first,
    read_record,
)
from mjcfbuild.outputs import mesh_depfile, product_summary
from mjcfbuild.steps.payloads import MeshOptions, MeshPayload
from mjcfbuild.steps.versions import MESH

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph
    from mjcfbuild.urdf.model import Robot


def _tasks(graph: Graph) -> list[dict]:
    paths, roles = graph.paths, graph.roles
    return [
        _mesh_task(
            graph.ctx,
            mesh_id,
            paths[mesh_id],
            roles[mesh_id],
            graph.prefix,
            graph.robot,
            graph.looks_from.get(mesh_id),
        )
        for mesh_id in largest_first(roles, lambda mesh_id: paths[mesh_id])
    ]


def _mesh_task(
    ctx: GraphContext,
    mesh_id: str,
    path: str,
    roles: list[str],
    prefix: str,
    robot: Robot,
    looks_from: str | None = None,
) -> dict:
    from mjcfbuild.urdf.mesh_uses import mesh_uses

    read, stale = discovered_inputs(ctx, mesh_depfile(ctx, mesh_id))
    meshes = ctx.manifest.meshes
    up_axis = up_axis_mode(meshes.collada_up_axis, meshes.collada_up_axis_files, path)
    options = MeshOptions(
        roles=roles,
        max_faces=meshes.max_faces,
        collada_up_axis=up_axis,
        # Each budget only for the product it shapes, so other products keep their cache keys.
        collision_max_faces=meshes.collision_max_faces if "collision" in roles else None,
        max_hull_vertices=meshes.max_hull_vertices if "hull" in roles else None,
    )
    payload = MeshPayload(
        options=options,
        max_file_bytes=int(meshes.max_file_mb * 1e6),
        source=path,
        product_dir=str(ctx.products_dir / mesh_id),
        summary=str(product_summary(ctx, mesh_id)),
        depfile=str(mesh_depfile(ctx, mesh_id)),
        cache=ctx.cache_settings(),
        evidence=[u.to_dict() for u in mesh_uses(robot, mesh_id)] if up_axis == "auto" else [],
        label=ctx.portable_label(path),
        named_at=_named_at(robot, mesh_id),
        looks_from=looks_from,
    )
    return file_task(
        ctx,
        FAMILY,
        f"{prefix}mesh:{mesh_id}",
        f"mesh {mesh_id}",
        payload,
        in_worker=True,
        file_dep=[Path(path), *([Path(looks_from)] if looks_from else []), *read],
        targets=[product_summary(ctx, mesh_id)],
        extra_uptodate=stale,
    )


def _verify(graph: Graph) -> None:
    """Refuse a ``meshes.collada_up_axis_files`` entry that matches no mesh file of the robot
    (a typo would leave the file it meant to the default without a word), at its robot.yaml
    line, with the closest file and the robot's DAE files."""
    from mjcfbuild.errors import ManifestError
    from mjcfbuild.manifest.pinpoint import key_segment, pinpoint
    from mjcfbuild.sources.packages import listing, suggestion

    ctx = graph.ctx
    paths = sorted(set(graph.paths.values()))
    for pattern in sorted(ctx.manifest.meshes.collada_up_axis_files):
        if any(_path_matches(path, pattern) for path in paths):
            continue
        tails = sorted({tail for path in paths for tail in _path_tails(path)})
        dae = sorted({Path(p).name for p in paths if p.lower().endswith(".dae")})
        error = ManifestError(
            f"'{pattern}' matches no mesh file of the robot{suggestion([pattern], tails)}",
            file=f"{ctx.manifest_label} meshes.collada_up_axis_files{key_segment(pattern)}",
            hint=f"fix the name, or remove the entry; the robot's DAE files: {listing(dae)}",
        )
        if ctx.manifest_file is not None:
            pinpoint(error, ctx.manifest_label, ctx.manifest_file)
        raise error


def _path_tails(path: str) -> list[str]:
    """The ends of a mesh file's path a pattern is likely to name: its file name, and its
    folder and file name."""
    parts = path.replace("\\", "/").split("/")
    return ["/".join(parts[-count:]) for count in (1, 2) if len(parts) >= count]


def _path_matches(path: str, pattern: str) -> bool:
    """Whether a ``collada_up_axis_files`` pattern names the mesh file ``path`` (it is matched
    against the end of the path)."""
    from fnmatch import fnmatchcase

    posix = path.replace("\\", "/")
    return fnmatchcase(posix, pattern) or fnmatchcase(posix, "*/" + pattern.lstrip("/"))


def _named_at(robot: Robot, mesh_id: str) -> str:
    """``file:line`` of the first URDF element naming the mesh ``mesh_id``, else ``""``."""
    for link in robot.links:
        for shape in link.shapes:
            geometry = shape.geometry
            line = geometry.line or shape.line  # its <mesh> element's, where known
            if geometry.kind == "mesh" and geometry.mesh_id == mesh_id and line:
                return f"{robot.source}:{line}"
    return ""


def up_axis_mode(mode: str, files: Mapping[str, str], path: str) -> str:
    """The up-axis option of one mesh file: a ``collada_up_axis_files`` entry matching the end
    of its path, else ``mode``; only DAE files are ever ``auto`` (other formats have no tag,
    and keep the product keys they had before ``auto`` existed)."""
    for pattern, choice in sorted(files.items()):
        if _path_matches(path, pattern):
            return choice
    if mode == "auto" and not path.lower().endswith(".dae"):
        return "ignore"
    return mode


def mesh_products(ctx: GraphContext) -> list[Path]:
    """The records of the mesh products of this build (``products/<id>.json`` beside the
    product's folder)."""
    return [p for p in sorted(ctx.products_dir.glob("*.json")) if (p.parent / p.stem).is_dir()]


def up_axis_decisions(ctx: GraphContext) -> list[dict]:
    """Per DAE file tagged other than Z-up: its mesh, whether it was turned, and why."""
    rows = []
    for path in mesh_products(ctx):
        decision = read_record(path).get("up_axis")
        if isinstance(decision, dict):
            rows.append({"mesh": path.stem, **decision})
    return rows


def _report(ctx: GraphContext) -> dict:
    return {"up_axis": up_axis_decisions(ctx), "products": {"meshes": len(mesh_products(ctx))}}


FAMILY = Family(
    name="mesh",
    step="mjcfbuild.steps.mesh:run",
    payload=MeshPayload,
    format=MESH.format,  # declared beside the step, which keys its products by it
    tools=MESH.tools,
    tasks=_tasks,
    verify=_verify,
    report=_report,
)
