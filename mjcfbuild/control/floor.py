"""The lowest point of a model's collision geometry, for standing robots on the floor."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class LowestPoint:
    """Height of the lowest collision point, and the body it belongs to."""

    height: float
    body: str


def lowest_collision_point(model, data) -> LowestPoint | None:
    """The lowest point of every colliding geom at ``data``'s pose (after kinematics).

    Exact for MuJoCo's primitives and for meshes (their vertices); planes, height fields and
    SDFs are ignored. None when the model has no colliding geom.
    """
    import mujoco

    points = geom_lowest_points(model, data)
    if not points:
        return None
    geom = min(points, key=lambda g: (points[g][2], g))
    body = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[geom])
    return LowestPoint(float(points[geom][2]), body or "world")


def geom_lowest_points(model, data) -> dict:
    """For every colliding geom: a point at its lowest height (x and y are its centre's for
    primitives, the lowest vertex's for meshes)."""
    import mujoco
    import numpy as np

    result = {}
    types = mujoco.mjtGeom
    for geom in range(model.ngeom):
        if model.geom_contype[geom] == 0 and model.geom_conaffinity[geom] == 0:
            continue
        kind = model.geom_type[geom]
        size = model.geom_size[geom]
        rotation = data.geom_xmat[geom].reshape(3, 3)
        centre = float(data.geom_xpos[geom][2])
        up = rotation[2]  # the world z row: how far each local axis reaches upwards
        if kind == types.mjGEOM_SPHERE:
            height = centre - size[0]
        elif kind == types.mjGEOM_CAPSULE:
            height = centre - abs(up[2]) * size[1] - size[0]
        elif kind == types.mjGEOM_CYLINDER:
            height = (
                centre - abs(up[2]) * size[1] - size[0] * float(np.sqrt(max(0.0, 1 - up[2] ** 2)))
            )
        elif kind == types.mjGEOM_BOX:
            height = centre - float(np.abs(up) @ size)
        elif kind == types.mjGEOM_ELLIPSOID:
            height = centre - float(np.sqrt(((up * size) ** 2).sum()))
        elif kind == types.mjGEOM_MESH:
            mesh = model.geom_dataid[geom]
            start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
            vertices = model.mesh_vert[start : start + count]
            lowest_vertex = vertices[int(np.argmin(vertices @ up))]
            point = data.geom_xpos[geom] + rotation @ lowest_vertex
            result[geom] = point
            continue
        else:
            continue
        point = data.geom_xpos[geom].copy()
        point[2] = height
        result[geom] = point
    return result
