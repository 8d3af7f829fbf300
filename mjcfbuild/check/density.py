"""How much volume a body's geometry holds, and whether its mass fits in it.

A robot is made of materials between foam and tungsten; a body whose mass over its geometry's
volume is far outside that has a mass in the wrong unit (grams written as kilograms) or meshes
at the wrong scale. The volume is bracketed, never guessed, so real descriptions (hollow shells,
visual meshes that enclose nothing, collision primitives larger than the part) are not named:

* the *upper bound* is, for the visual and for the collision geometry each, the sum of its
  geoms' convex hull volumes; the larger of the two. A mass too heavy even for that is judged;
* the *lower bound* is the largest volume one geom certainly encloses: a primitive's, or a
  closed mesh's (every edge shared by two faces), never more than its hull. A mass too light
  even for that is judged. Open meshes enclose nothing and add nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from mjcfbuild.numbers import beside

if TYPE_CHECKING:
    import mujoco

# Robots are made of foam and hollow shells (about 100 kg/m^3) up to steel and tungsten
# counterweights (8,000 to 19,000): outside these bounds a mass or a scale is wrong.
LOW_DENSITY = 50.0
HIGH_DENSITY = 25000.0
# The density the decades off are counted from (of the order of plastics and aluminium).
TYPICAL_DENSITY = 1000.0
# Ten times beyond the bounds is a unit (grams, tonnes, meshes in cm or mm) and fails the
# check. Nearer, real descriptions have reasons: a collision primitive drawn larger than the
# part, a placeholder mass, wheels given 100 kg for a stable simulation; a warning.
FAILING_LOW_DENSITY = LOW_DENSITY / 10
FAILING_HIGH_DENSITY = HIGH_DENSITY * 10


@dataclass(frozen=True)
class Volume:
    """Bounds of the volume some geometry encloses, in m^3."""

    low: float
    high: float


def body_volumes(model: mujoco.MjModel) -> dict[int, Volume]:
    """The volume bounds of each body's geometry (planes excluded), by body id; bodies
    without geometry are absent."""
    import mujoco

    hulls: dict[int, dict[bool, float]] = {}
    enclosed: dict[int, float] = {}
    meshes: dict[int, tuple[float, float]] = {}
    for index in range(model.ngeom):
        kind = model.geom_type[index]
        if kind == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        body = int(model.geom_bodyid[index])
        if kind == mujoco.mjtGeom.mjGEOM_MESH and model.geom_dataid[index] >= 0:
            mesh = int(model.geom_dataid[index])
            if mesh not in meshes:
                meshes[mesh] = mesh_volume(model, mesh)
            inside, hull = meshes[mesh]
        else:
            size = [float(v) for v in model.geom_size[index]]
            inside = hull = primitive_volume(int(kind), size)
        visual = model.geom_contype[index] == 0 and model.geom_conaffinity[index] == 0
        roles = hulls.setdefault(body, {True: 0.0, False: 0.0})
        roles[bool(visual)] += hull
        enclosed[body] = max(enclosed.get(body, 0.0), inside)
    return {body: Volume(enclosed[body], max(roles.values())) for body, roles in hulls.items()}


def primitive_volume(kind: int, size: list[float]) -> float:
    """The volume of a MuJoCo primitive of type ``kind`` and ``size`` (half sizes, radii)."""
    import mujoco

    geom = mujoco.mjtGeom
    if kind == geom.mjGEOM_SPHERE:
        return 4.0 / 3.0 * math.pi * size[0] ** 3
    if kind == geom.mjGEOM_CAPSULE:
        return math.pi * size[0] ** 2 * (2.0 * size[1] + 4.0 / 3.0 * size[0])
    if kind == geom.mjGEOM_CYLINDER:
        return math.pi * size[0] ** 2 * 2.0 * size[1]
    if kind == geom.mjGEOM_ELLIPSOID:
        return 4.0 / 3.0 * math.pi * size[0] * size[1] * size[2]
    if kind == geom.mjGEOM_BOX:
        return 8.0 * size[0] * size[1] * size[2]
    return 0.0  # height fields and SDFs: no bound claimed


def mesh_volume(model: mujoco.MjModel, mesh: int) -> tuple[float, float]:
    """(volume the mesh certainly encloses, its convex hull's volume); the first is 0 for an
    open mesh, which encloses nothing for sure."""
    import numpy as np
    from scipy.spatial import ConvexHull, QhullError

    start, count = int(model.mesh_vertadr[mesh]), int(model.mesh_vertnum[mesh])
    vertices = np.asarray(model.mesh_vert[start : start + count], dtype=float)
    first, faces = int(model.mesh_faceadr[mesh]), int(model.mesh_facenum[mesh])
    triangles = np.asarray(model.mesh_face[first : first + faces], dtype=np.int64)
    try:
        hull = float(ConvexHull(vertices).volume) if count >= 4 else 0.0
    except (QhullError, ValueError):  # flat or degenerate: no volume
        hull = 0.0
    if not len(triangles) or not _closed(triangles):
        return 0.0, hull
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    signed = float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum()) / 6.0
    return min(abs(signed), hull), hull


def _closed(triangles) -> bool:
    """Whether every edge of the triangles is shared by exactly two of them."""
    import numpy as np

    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    # One integer per undirected edge, sorted: closed means the keys come in pairs, each
    # pair different from the next (a row-wise np.unique took 0.2 s on panda's meshes).
    low, high = edges.min(axis=1), edges.max(axis=1)
    keys = np.sort(low * (int(high.max()) + 1) + high)
    if len(keys) % 2:
        return False
    firsts, seconds = keys[0::2], keys[1::2]
    return bool(np.all(firsts == seconds) and np.all(seconds[:-1] < firsts[1:]))


def density_problem(mass: float, volume: Volume) -> tuple[str, float] | None:
    """(what is wrong, the density judged) when ``mass`` cannot fill ``volume``; else None."""
    if volume.high > 0 and mass / volume.high > HIGH_DENSITY:
        density = mass / volume.high
        return (
            f"its mass {mass:.4g} kg in at most {volume.high:.3g} m^3 of geometry is "
            f"{beside(density, HIGH_DENSITY)} kg/m^3, denser than anything robots are made of "
            f"(at most {HIGH_DENSITY:,.0f})",
            density,
        )
    if volume.low > 0 and mass / volume.low < LOW_DENSITY:
        density = mass / volume.low
        return (
            f"its mass {mass:.4g} kg in at least {volume.low:.3g} m^3 of geometry is "
            f"{beside(density, LOW_DENSITY)} kg/m^3, lighter than anything robots are made of "
            f"(at least {LOW_DENSITY:,.0f})",
            density,
        )
    return None


def density_fails(density: float) -> bool:
    """Whether an implausible ``density`` fails the check (else it is a warning)."""
    return bool(density > FAILING_HIGH_DENSITY or density < FAILING_LOW_DENSITY)


def density_cause(density: float) -> str:
    """The likely cause of an implausible ``density``, with what to do."""
    decades = round(math.log10(density / TYPICAL_DENSITY))
    if decades == 2:
        return (
            "a mass far too large for the part: ballast written for a stable simulation, or a "
            "mass in grams written as kilograms; give the <inertial> the part's real mass"
        )
    if decades >= 3:
        if decades <= 4:
            return (
                f"a mass in grams written as kilograms (about 10^{decades} too heavy): divide "
                "the <inertial> mass and inertia by 1000"
            )
        return (
            f"units off by about 10^{decades}: a mass in grams or smaller units written as "
            "kilograms, or meshes scaled too small; fix the <inertial> mass and inertia, or "
            "the mesh's scale"
        )
    if decades >= 1:
        return "a mass too large for the part: check the <inertial> mass and the geometry's size"
    if decades <= -8:
        return (
            f"a missing scale (about 10^{decades}): meshes in mm read as metres; scale them "
            'by 0.001 (<mesh scale="0.001 0.001 0.001"/>) or export them in metres'
        )
    if decades <= -5:
        return (
            f"a missing scale (about 10^{decades}): meshes in cm read as metres; scale them "
            'by 0.01 (<mesh scale="0.01 0.01 0.01"/>)'
        )
    if decades <= -3:
        return (
            f"a mass in tonnes written as kilograms, or a placeholder mass (about 10^{decades} "
            "too light): give the <inertial> the part's real mass"
        )
    return "a placeholder mass, or geometry much larger than the part: check the <inertial> mass"
