"""How far convex collision geometry stands off the mesh it replaces.

The measure is the largest distance from a point on the outer surface of the convex geometry
(one hull, or the union of a decomposition's parts) to the mesh's surface, in CoACD's units:
relative to half the mesh's largest bounding-box extent, the scale CoACD normalises a mesh to
before comparing its concavity with ``threshold``. So a hull measured at 0.04 is one CoACD
would accept at ``threshold: 0.05`` without cutting, and a decomposition's figure says how
closely its parts follow the mesh in the units the user asked for.

It is defined for any triangle soup (watertight or not), unlike a volume ratio, and it is the
error a contact sees: a point of the collision geometry that far from the real surface. Only
the outward direction counts: faces inside the mesh (internal walls) are covered by the
geometry and never touched.

Points are sampled with a fixed seed, and each is measured exactly against the triangles near
it, so the same input always gives the same figure.
"""

from __future__ import annotations

import numpy as np

# Samples of the convex geometry's surface, and of the mesh's surface to find nearby triangles.
GEOMETRY_SAMPLES = 4000
MESH_SAMPLES = 20000
NEAREST = 8
_SEED = 0


def scale(vertices: np.ndarray) -> float:
    """Half the largest bounding-box extent: CoACD's unit of concavity for this mesh."""
    extents = vertices.max(axis=0) - vertices.min(axis=0)
    return float(extents.max()) / 2 or 1.0


def hull_concavity(vertices: np.ndarray, faces: np.ndarray) -> float:
    """How far the convex hull of the mesh stands off the mesh (see the module)."""
    import trimesh

    hull = trimesh.Trimesh(vertices=vertices, process=False).convex_hull
    return parts_concavity(vertices, faces, [(hull.vertices, hull.faces)])


def parts_concavity(
    vertices: np.ndarray, faces: np.ndarray, parts: list[tuple[np.ndarray, np.ndarray]]
) -> float:
    """How far the union of convex ``parts`` (vertices, faces) stands off the mesh."""
    rng = np.random.default_rng(_SEED)
    points = _outer_points(parts, rng)
    if len(points) == 0:
        return 0.0
    distance = _distance_to_surface(vertices, faces, points, rng, outside_only=len(parts) > 1)
    return round(float(distance.max()) / scale(vertices), 6)


def _outer_points(parts: list[tuple[np.ndarray, np.ndarray]], rng: np.random.Generator):
    """Points on the parts' surfaces that are not inside or on another part.

    Points on a face two parts share (a CoACD cut) lie inside the mesh, not on the union's
    outer surface; a margin of 1e-4 of the parts' size treats them as covered.
    """
    margin = 1e-4 * scale(np.concatenate([v for v, _ in parts]))
    areas = np.array([_triangle_areas(v, f).sum() for v, f in parts])
    total = areas.sum()
    if total <= 0:
        return np.zeros((0, 3))
    samples = []
    for index, (v, f) in enumerate(parts):
        count = max(1, int(GEOMETRY_SAMPLES * areas[index] / total + 0.5))
        points = _sample_surface(v, f, count, rng)
        for other, (ov, of) in enumerate(parts):
            if other != index and len(points):
                points = points[~_covered(ov, of, points, margin)]
        samples.append(points)
    return np.concatenate(samples)


def _covered(vertices: np.ndarray, faces: np.ndarray, points: np.ndarray, margin: float):
    """Which points lie inside the convex hull of ``vertices`` or within ``margin`` of it."""
    triangles = vertices[faces]
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    keep = lengths > 0
    normals = normals[keep] / lengths[keep, None]
    centre = vertices.mean(axis=0)
    offsets = np.einsum("ij,ij->i", normals, triangles[keep, 0])
    # Orient every plane outward (hull faces from CoACD are not always wound alike).
    flip = normals @ centre > offsets
    normals[flip] *= -1
    offsets[flip] *= -1
    return np.all(points @ normals.T <= offsets + margin, axis=1)


def _distance_to_surface(vertices, faces, points, rng, outside_only: bool) -> np.ndarray:
    """Distance from each point to the mesh surface, exact against the triangles nearby.

    The triangles of a point's nearest surface samples, and their neighbours across an edge
    (the nearest triangle of a point near an edge may have no sample among the nearest).
    With ``outside_only``, points behind their nearest triangle (inside the mesh: faces of
    parts that CoACD cut apart and that do not quite meet) count as on the surface.
    """
    import trimesh
    from scipy.spatial import cKDTree

    mesh = trimesh.Trimesh(vertices, faces, process=True)  # merged, so edges are shared
    vertices, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    areas = _triangle_areas(vertices, faces)
    if areas.sum() <= 0:
        return np.zeros(len(points))
    count = max(MESH_SAMPLES, len(faces))
    chosen = rng.choice(len(faces), size=count, p=areas / areas.sum())
    chosen = np.concatenate([np.arange(len(faces)), chosen])  # every triangle at least once
    samples = _points_on(vertices[faces[chosen]], rng)
    _, nearest = cKDTree(samples).query(points, k=min(NEAREST, len(samples)))
    nearby = _with_neighbours(len(faces), mesh.face_adjacency)
    candidates = nearby[chosen[nearest.reshape(len(points), -1)]].reshape(len(points), -1)
    repeated = np.repeat(points, candidates.shape[1], axis=0)
    closest = trimesh.triangles.closest_point(vertices[faces[candidates.ravel()]], repeated)
    distances = np.linalg.norm(closest - repeated, axis=1).reshape(candidates.shape)
    rows = np.arange(len(points))
    best = distances.argmin(axis=1)
    result = distances[rows, best]
    if outside_only:
        nearest_point = closest.reshape(*candidates.shape, 3)[rows, best]
        normals = mesh.face_normals[candidates[rows, best]] * _orientation(vertices, faces)
        behind = np.einsum("ij,ij->i", points - nearest_point, normals) < 0
        result[behind] = 0.0
    return result


def _orientation(vertices: np.ndarray, faces: np.ndarray) -> float:
    """1 if the triangles face outward (positive enclosed volume, also for a mesh with small
    holes), else -1."""
    a, b, c = (vertices[faces[:, i]] - vertices.mean(axis=0) for i in range(3))
    return 1.0 if np.einsum("ij,ij->i", a, np.cross(b, c)).sum() >= 0 else -1.0


def _with_neighbours(count: int, adjacency: np.ndarray) -> np.ndarray:
    """Per triangle: itself and up to three triangles sharing an edge with it (else itself)."""
    table = np.repeat(np.arange(count)[:, None], 4, axis=1)
    if len(adjacency) == 0:
        return table
    pairs = np.concatenate([adjacency, adjacency[:, ::-1]])
    pairs = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]
    slot = np.arange(len(pairs)) - np.searchsorted(pairs[:, 0], pairs[:, 0], side="left")
    keep = slot < 3  # a non-manifold edge can have more; three are enough to find the nearest
    table[pairs[keep, 0], 1 + slot[keep]] = pairs[keep, 1]
    return table


def _points_on(triangles: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """One uniformly distributed point on each triangle."""
    bary = rng.random((len(triangles), 2))
    flip = bary.sum(axis=1) > 1
    bary[flip] = 1 - bary[flip]
    origin = triangles[:, 0]
    return (
        origin + bary[:, :1] * (triangles[:, 1] - origin) + bary[:, 1:] * (triangles[:, 2] - origin)
    )


def _sample_surface(vertices, faces, count: int, rng: np.random.Generator) -> np.ndarray:
    areas = _triangle_areas(vertices, faces)
    if areas.sum() <= 0:
        return np.zeros((0, 3))
    chosen = rng.choice(len(faces), size=count, p=areas / areas.sum())
    points = _points_on(vertices[faces[chosen]], rng)
    # Corners too: where parts stick out furthest, random samples may miss.
    return np.concatenate([points, vertices])


def _triangle_areas(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    triangles = vertices[faces]
    cross = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    return np.linalg.norm(cross, axis=1) / 2
