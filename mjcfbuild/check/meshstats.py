"""Mesh statistics per body: visual and collision vertices and faces, convex parts."""

from __future__ import annotations


def mesh_statistics(model) -> list[dict]:
    """One row per body with meshes, in body order."""
    import mujoco

    rows: dict[int, dict] = {}
    for geom in range(model.ngeom):
        mesh = model.geom_dataid[geom]
        if model.geom_type[geom] != mujoco.mjtGeom.mjGEOM_MESH or mesh < 0:
            continue
        body = int(model.geom_bodyid[geom])
        row = rows.setdefault(
            body,
            {
                "body": mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or "world",
                "visual_vertices": 0,
                "visual_faces": 0,
                "collision_vertices": 0,
                "collision_faces": 0,
                "convex_parts": 0,
            },
        )
        collides = model.geom_contype[geom] or model.geom_conaffinity[geom]
        kind = "collision" if collides else "visual"
        row[f"{kind}_vertices"] += int(model.mesh_vertnum[mesh])
        row[f"{kind}_faces"] += int(model.mesh_facenum[mesh])
        if collides:
            row["convex_parts"] += 1
    return [rows[body] for body in sorted(rows)]
