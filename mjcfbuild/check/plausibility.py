"""Are the meshes where they belong? A cheap test that needs no URDF, for every mesh format.

Load, simulation, forward kinematics and masses can all match the URDF while a mesh sits in
the wrong place: a COLLADA file read with the wrong up axis, a mesh exported in millimetres, a
mesh with a wrong origin. Two facts of every real link catch those: its centre of mass lies
inside (or close to) its own geometry, and its visual and collision geometry overlap. For each
body with mass and geometry, in the body's frame:

* the bounding box of its geoms (every vertex of a mesh geom; the corners of a primitive's
  bounding box) should hold its centre of mass, within a margin;
* the box of its visual geoms and the box of its collision geoms should overlap.

A body that fails is named with the likely cause: *units in mm* when one of its meshes is
hundreds of times larger than the rest of its geometry (or than the robot, when it has no
other); *up axis* when a mesh turned by a quarter turn about x or y (a file's Y_UP or X_UP
tag applied or not) passes both tests; else *a wrong origin*. Meshes in millimetres fail the
check (the model is certainly wrong); the other causes are warnings, since a hand-made model
can have a light shell around a heavy counterweight.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import mujoco
    import numpy as np

# A centre of mass this far outside its body's box (a fraction of the box's diagonal, plus an
# absolute slack for small links) is not inside it.
COM_MARGIN = 0.2
COM_SLACK = 0.01
# A mesh this many times larger than its body's other geometry (or than the robot) is in mm.
MM_RATIO = 100.0
# Bodies lighter than this (dummy frames, sensors' placeholders) say nothing.
MIN_MASS = 1e-3


@dataclass
class BodyFinding:
    """One body that failed the test, and why it likely did."""

    body: str
    problems: list[str]
    cause: str  # "units in mm", "up axis" or "wrong origin"
    detail: str
    fails: bool  # a failure of the check; else a warning

    def text(self) -> str:
        """The one-line message."""
        return f"body '{self.body}': {'; '.join(self.problems)}; likely cause: {self.detail}"


@dataclass
class Plausibility:
    """The test's result for a model."""

    bodies: int = 0  # bodies tested
    findings: list[BodyFinding] = field(default_factory=list)

    @property
    def failures(self) -> list[str]:
        """Messages of the findings that fail the check."""
        return [f.text() for f in self.findings if f.fails]

    @property
    def warnings(self) -> list[str]:
        """Messages of the findings that are warnings."""
        return [f.text() for f in self.findings if not f.fails]

    def to_dict(self) -> dict:
        """The result as check.json holds it."""
        return {
            "bodies": self.bodies,
            "findings": [asdict(f) for f in self.findings],
            "failures": self.failures,
            "warnings": self.warnings,
        }


@dataclass
class _Geom:
    name: str
    visual: bool
    is_mesh: bool
    points: np.ndarray  # in the body frame
    file_origin: np.ndarray | None = None  # a mesh's file frame in the body frame
    file_axes: np.ndarray | None = None
    file_points: np.ndarray | None = None  # the vertices in the mesh file's frame


def check_plausibility(model: mujoco.MjModel, skip: set[str] | None = None) -> Plausibility:
    """Test every body of ``model`` with mass and geometry (except those named in ``skip``)."""
    import mujoco

    result = Plausibility()
    geoms_of: dict[int, list[_Geom]] = {}
    for index in range(model.ngeom):
        if model.geom_type[index] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        geoms_of.setdefault(int(model.geom_bodyid[index]), []).append(_geom(model, index))
    sizes = [_diagonal(g.points) for geoms in geoms_of.values() for g in geoms]
    robot_size = _robot_size(model)
    for body, geoms in sorted(geoms_of.items()):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or f"body {body}"
        if body == 0 or model.body_mass[body] < MIN_MASS or name in (skip or set()):
            continue
        result.bodies += 1
        com = model.body_ipos[body].copy()
        problems = _problems(geoms, com)
        if not problems:
            continue
        result.findings.append(_diagnose(name, geoms, com, problems, sizes, robot_size))
    return result


def _geom(model: mujoco.MjModel, index: int) -> _Geom:
    import mujoco
    import numpy as np

    flat = np.zeros(9)
    mujoco.mju_quat2Mat(flat, model.geom_quat[index])
    rotation = flat.reshape(3, 3)
    position = model.geom_pos[index]
    visual = model.geom_contype[index] == 0 and model.geom_conaffinity[index] == 0
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, index) or f"geom {index}"
    mesh = model.geom_dataid[index]
    if model.geom_type[index] == mujoco.mjtGeom.mjGEOM_MESH and mesh >= 0:
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        local = model.mesh_vert[start : start + count].astype(float)
        mesh_flat = np.zeros(9)
        mujoco.mju_quat2Mat(mesh_flat, model.mesh_quat[mesh])
        mesh_rotation = mesh_flat.reshape(3, 3)
        # MuJoCo centres a mesh on its inertia frame; undo that to find the file's own frame.
        axes = rotation @ mesh_rotation.T
        origin = position - axes @ model.mesh_pos[mesh]
        in_file = local @ mesh_rotation.T + model.mesh_pos[mesh]
        mesh_name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_MESH, mesh) or name
        return _Geom(mesh_name, visual, True, local @ rotation.T + position, origin, axes, in_file)
    center, half = model.geom_aabb[index][:3], model.geom_aabb[index][3:]
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    corners = center + signs * half
    return _Geom(name, visual, False, corners @ rotation.T + position)


def _diagonal(points: np.ndarray) -> float:
    import numpy as np

    return float(np.linalg.norm(points.max(axis=0) - points.min(axis=0))) if len(points) else 0.0


def _robot_size(model: mujoco.MjModel) -> float:
    """The spread of the bodies' origins at qpos0: how big the kinematics say the robot is."""
    import mujoco
    import numpy as np

    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return _diagonal(np.asarray(data.xpos[1:])) if model.nbody > 2 else 0.0


def _problems(geoms: list[_Geom], com: np.ndarray) -> list[str]:
    import numpy as np

    problems = []
    everything = np.concatenate([g.points for g in geoms])
    low, high = everything.min(axis=0), everything.max(axis=0)
    outside = float(np.linalg.norm(np.maximum(low - com, 0) + np.maximum(com - high, 0)))
    allowed = COM_MARGIN * float(np.linalg.norm(high - low)) + COM_SLACK
    if outside > allowed:
        problems.append(f"its centre of mass is {outside:.3g} m outside its geometry")
    visual = [g.points for g in geoms if g.visual]
    collision = [g.points for g in geoms if not g.visual]
    if visual and collision:
        a, b = np.concatenate(visual), np.concatenate(collision)
        pad = 0.05 * max(_diagonal(a), _diagonal(b))
        gap = np.maximum(a.min(axis=0) - b.max(axis=0), b.min(axis=0) - a.max(axis=0))
        if np.any(gap > pad):
            apart = float(np.linalg.norm(np.maximum(gap, 0)))
            problems.append(f"its visual and collision geometry are {apart:.3g} m apart")
    return problems


def _diagnose(
    body: str,
    geoms: list[_Geom],
    com: np.ndarray,
    problems: list[str],
    sizes: list[float],
    robot_size: float,
) -> BodyFinding:
    import numpy as np

    meshes = [g for g in geoms if g.is_mesh]
    for mesh in meshes:
        size = _diagonal(mesh.points)
        own = [_diagonal(g.points) for g in geoms if g.name != mesh.name]
        others = [s for s in own if s > 0] or [s for s in sizes if 0 < s < size]
        reference = float(np.median(others)) if others else robot_size
        if reference > 0 and size >= MM_RATIO * reference:
            return BodyFinding(
                body,
                problems,
                "units in mm",
                f"units in mm: mesh '{mesh.name}' is {size / reference:.0f} times the size of "
                f"{'its body' if own else 'the robot'}'s other geometry; scale it by 0.001 "
                "(the URDF's <mesh scale>) or export it in metres",
                True,
            )
    for label, turn in _QUARTER_TURNS:
        trial = [_turned(g, turn) if g.is_mesh else g for g in geoms]
        if meshes and not _problems(trial, com):
            names = ", ".join(sorted({f"'{m.name}'" for m in meshes}))
            return BodyFinding(
                body,
                problems,
                "up axis",
                f"up axis: mesh {names} fits once turned {label}; for a DAE file set "
                "meshes.collada_up_axis_files for it in robot.yaml (apply or ignore), else "
                "turn the visual's <origin rpy>",
                False,
            )
    return BodyFinding(
        body,
        problems,
        "wrong origin",
        "a wrong origin: check the <origin> of its visual, collision and inertial elements, "
        "and the mesh file's own origin",
        False,
    )


def _turned(geom: _Geom, turn: list[list[int]]) -> _Geom:
    """``geom``'s mesh turned about its file's own origin."""
    import numpy as np

    assert geom.file_points is not None and geom.file_axes is not None
    assert geom.file_origin is not None
    moved = (geom.file_points @ np.asarray(turn, float).T) @ geom.file_axes.T + geom.file_origin
    return _Geom(geom.name, geom.visual, True, moved)


_QUARTER_TURNS = [
    ("a quarter turn about x (Y-up data read as Z-up)", [[1, 0, 0], [0, 0, -1], [0, 1, 0]]),
    ("a quarter turn back about x (Z-up data turned as Y-up)", [[1, 0, 0], [0, 0, 1], [0, -1, 0]]),
    ("a quarter turn about y (X-up data read as Z-up)", [[0, 0, -1], [0, 1, 0], [1, 0, 0]]),
    ("a quarter turn back about y", [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]),
]
