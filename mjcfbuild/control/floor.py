"""The lowest points of a model's collision geometry, and points on it, for standing robots on
the floor."""

from __future__ import annotations

import math
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
    return _lowest_point(model, data, colliding=True)


def lowest_visual_point(model, data) -> LowestPoint | None:
    """The lowest point of every geom that does not collide (the visual geometry) at
    ``data``'s pose (after kinematics), as :func:`lowest_collision_point` finds it; for a
    model with no collision geometry, which has nothing else to place the floor under."""
    return _lowest_point(model, data, colliding=False)


def _lowest_point(model, data, colliding: bool) -> LowestPoint | None:
    import mujoco

    points = geom_lowest_points(model, data, colliding=colliding)
    if not points:
        return None
    geom = min(points, key=lambda g: (points[g][2], g))
    body = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[geom])
    return LowestPoint(float(points[geom][2]), body or "world")


def geom_lowest_points(model, data, colliding: bool = True) -> dict:
    """For every colliding geom of the robot (every other geom, without ``colliding``): a
    point at its lowest height (x and y are its centre's for primitives, the lowest vertex's
    for meshes). In a floating model, geometry welded to the world (a root link that holds
    the robot by a floating joint) is the ground, not the robot, and is left out."""
    import mujoco

    floats = mujoco.mjtJoint.mjJNT_FREE in model.jnt_type
    result = {}
    for geom in range(model.ngeom):
        collides = bool(model.geom_contype[geom] or model.geom_conaffinity[geom])
        if collides != colliding:
            continue
        if floats and model.body_weldid[model.geom_bodyid[geom]] == 0:
            continue
        point = geom_lowest_points_of(model, data, geom)
        if point is not None:
            result[geom] = point
    return result


def geom_lowest_points_of(model, data, geom: int):
    """A point at ``geom``'s lowest height, or None for planes, height fields and SDFs."""
    import mujoco
    import numpy as np

    types = mujoco.mjtGeom
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
        height = centre - abs(up[2]) * size[1] - size[0] * float(np.sqrt(max(0.0, 1 - up[2] ** 2)))
    elif kind == types.mjGEOM_BOX:
        height = centre - float(np.abs(up) @ size)
    elif kind == types.mjGEOM_ELLIPSOID:
        height = centre - float(np.sqrt(((up * size) ** 2).sum()))
    elif kind == types.mjGEOM_MESH:
        mesh = model.geom_dataid[geom]
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        vertices = model.mesh_vert[start : start + count]
        lowest_vertex = vertices[int(np.argmin(vertices @ up))]
        return data.geom_xpos[geom] + rotation @ lowest_vertex
    else:
        return None
    point = data.geom_xpos[geom].copy()
    point[2] = height
    return point


def body_points(model, data, body: int):
    """Points on the collision geometry of ``body`` in world coordinates: mesh vertices, and
    for primitives their corners and rims."""
    import numpy as np

    chunks = []
    for geom in range(model.ngeom):
        if model.geom_bodyid[geom] != body:
            continue
        if not (model.geom_contype[geom] or model.geom_conaffinity[geom]):
            continue
        points = geom_points(model, data, geom)
        if points is not None:
            chunks.append(points)
    return np.concatenate(chunks) if chunks else np.zeros((0, 3))


def geom_points(model, data, geom: int):
    """Points on ``geom`` in world coordinates (mesh vertices; corners and rims of
    primitives), or None for a plane or a height field."""
    local = _local_points(model, geom)
    if local is None:
        return None
    rotation = data.geom_xmat[geom].reshape(3, 3)
    return local @ rotation.T + data.geom_xpos[geom]


def geom_support_points(model, data, geom: int, tolerance: float) -> list:
    """The points of ``geom`` within ``tolerance`` of the floor (z = 0), its lowest included:
    where it can push on the floor.

    A curved surface touches the floor where it is lowest, not over the band of it that is
    within ``tolerance``: a sphere or an ellipsoid at one point, a capsule at the lowest
    point of each end (one, or a line lying down), a cylinder at its rims' lowest points
    unless a whole rim is that close (standing on a cap: the cap). Flat faces (boxes, mesh
    soles) keep every point that close: a sole tilted by a hair still stands on its area."""
    import mujoco

    lowest = geom_lowest_points_of(model, data, geom)
    kind = mujoco.mjtGeom(model.geom_type[geom])
    if kind in (mujoco.mjtGeom.mjGEOM_SPHERE, mujoco.mjtGeom.mjGEOM_ELLIPSOID):
        found = []
    elif kind == mujoco.mjtGeom.mjGEOM_CAPSULE:
        found = [p for p in _capsule_ends(model, data, geom) if p[2] <= tolerance]
    elif kind == mujoco.mjtGeom.mjGEOM_CYLINDER:
        found = _rim_support(model, data, geom, tolerance)
    else:
        points = geom_points(model, data, geom)
        found = [] if points is None else [p for p in points if p[2] <= tolerance]
    return [*found, *([lowest] if lowest is not None else [])]


def _capsule_ends(model, data, geom: int) -> list:
    """The lowest point of each of a capsule's two hemispherical ends, in world coordinates."""
    import numpy as np

    radius, half = model.geom_size[geom][:2]
    axis = data.geom_xmat[geom].reshape(3, 3)[:, 2]
    ends = []
    for sign in (1.0, -1.0):
        point = np.array(data.geom_xpos[geom] + sign * half * axis, dtype=float)
        point[2] -= radius
        ends.append(point)
    return ends


def _rim_support(model, data, geom: int, tolerance: float) -> list:
    """A cylinder's points on the floor: each rim whole where all of it is within
    ``tolerance`` of its lowest point (a cap flat on the floor), else the rim's lowest point
    where that is within ``tolerance``."""
    import numpy as np

    points = geom_points(model, data, geom)
    if points is None:
        return []
    found = []
    for rim in (points[:RIM_POINTS], points[RIM_POINTS : 2 * RIM_POINTS]):
        low = float(rim[:, 2].min())
        if low > tolerance:
            continue
        if float(rim[:, 2].max()) - low <= tolerance:
            found += [p for p in rim if p[2] <= tolerance]
        else:
            found.append(rim[int(np.argmin(rim[:, 2]))])
    return found


RIM_POINTS = 48  # points on each circle of a primitive (_local_points)


def _local_points(model, geom: int):
    """A geom's points in its own frame, or None for a plane or a height field."""
    import mujoco
    import numpy as np

    kind = mujoco.mjtGeom(model.geom_type[geom])  # an enum: `in` needs one
    size = model.geom_size[geom]
    circle = np.linspace(0, 2 * math.pi, RIM_POINTS, endpoint=False)
    ring = np.stack([np.cos(circle), np.sin(circle), np.zeros_like(circle)], axis=1)
    if kind == mujoco.mjtGeom.mjGEOM_MESH:
        mesh = model.geom_dataid[geom]
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        return np.asarray(model.mesh_vert[start : start + count], dtype=float)
    if kind == mujoco.mjtGeom.mjGEOM_SPHERE:
        great = np.concatenate([ring, ring[:, [0, 2, 1]], ring[:, [2, 0, 1]]])
        return great * size[0]
    if kind in (mujoco.mjtGeom.mjGEOM_CYLINDER, mujoco.mjtGeom.mjGEOM_CAPSULE):
        radius, half = size[0], size[1]
        rims = [ring * radius + [0, 0, half], ring * radius - [0, 0, half]]
        if kind == mujoco.mjtGeom.mjGEOM_CAPSULE:
            rims.append(np.array([[0, 0, half + radius], [0, 0, -half - radius]]))
        return np.concatenate(rims)
    if kind == mujoco.mjtGeom.mjGEOM_ELLIPSOID:
        return np.concatenate([ring, ring[:, [0, 2, 1]], ring[:, [2, 0, 1]]]) * size
    if kind == mujoco.mjtGeom.mjGEOM_BOX:
        return np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * size
    return None
