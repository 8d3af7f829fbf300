"""Are the meshes where they belong? A cheap test that needs no URDF, for every mesh format.

Load, simulation, forward kinematics and masses can all match the URDF while a mesh sits in
the wrong place: a COLLADA file read with the wrong up axis, a mesh exported in millimetres, a
mesh with a wrong origin. Facts of every real link catch those. For each body with mass and
geometry, in the body's frame:

* the bounding box of its geoms (every vertex of a mesh geom; the corners of a primitive's
  bounding box), and that of its visual geoms alone, should hold its centre of mass, within
  a margin;
* the box of its visual geoms and the box of its collision geoms should overlap (the larger
  covering at least a sliver of the smaller: collision geometry may stand beside its visual
  where a neighbouring link carries it, as on Baxter's elbows);
* no mesh should be metres across and a hundred times the body's other geometry (or, with none,
  the robot's joint layout): a robot whose meshes are all in mm keeps every centre of mass
  inside them, so this is a problem in itself;
* its mass should fit the volume of its geometry, and the robot's total mass all of it
  (check.mass_findings: a mass in grams or tonnes, a missing scale).

A body that fails is named with the likely cause, tried in order: *units in mm* (the last
test); *up axis*, when the meshes that came from DAE files tagged Y-up or X-up, turned a quarter
turn about x or y, pass every test and, where the body has collision geometry of its own (not
those meshes), overlap it better turned than as read (a centre of mass that fits a turned mesh
is no evidence when the mesh as read already agrees with its collision primitives); *a wrong
inertial origin*, when visual and collision geometry agree and the centre of mass is outside
both; else *a wrong origin*. Meshes in millimetres fail the check (the model is certainly
wrong); the other causes are warnings, since a hand-made model can have a light shell around a
heavy counterweight.

A body that passes is still named when a DAE mesh the build turned to Z-up (as its tag says,
by ``auto`` or robot.yaml's ``apply``) overlaps its body's own collision geometry clearly better
as the file is written: the turn took it away from the collision primitives it was drawn with,
and the box tests alone let an L-shaped pair of boxes pass.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.check.findings import BodyFinding
from mjcfbuild.urdf.model import Robot

if TYPE_CHECKING:
    import mujoco
    import numpy as np

    from mjcfbuild.check.loading import AssetSource
    from mjcfbuild.meshes.upaxis import UpAxisDecision

# A centre of mass this far outside its body's box (a fraction of the box's diagonal, plus an
# absolute slack for small links) is not inside it.
COM_MARGIN = 0.2
COM_SLACK = 0.01
# A mesh this many times larger than its body's other geometry (or than the robot), and at
# least MM_SIZE metres across, is in mm.
MM_RATIO = 100.0
MM_SIZE = 2.0
# Visual and collision boxes sharing less than this fraction of the smaller box do not overlap
# (real links have collision geometry beside their visual, authored on a neighbouring link).
MIN_SHARED = 0.02
# Bodies lighter than this (dummy frames, sensors' placeholders) say nothing.
MIN_MASS = 1e-3
# A mesh turned as its up axis says is turned away from its collision geometry when, as the file
# is written, its box's intersection over union with that geometry's is at least AWAY_FIT and
# the turned one's at most AWAY_RATIO of it. A quarter turn suggested by the check must raise
# that overlap by more than CLEARER to count as evidence.
AWAY_FIT = 0.25
AWAY_RATIO = 0.5
CLEARER = 0.05


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


@dataclass(eq=False)  # compared by identity
class _Geom:
    name: str
    visual: bool
    is_mesh: bool
    points: np.ndarray  # in the body frame
    file_origin: np.ndarray | None = None  # a mesh's file frame in the body frame
    file_axes: np.ndarray | None = None
    file_points: np.ndarray | None = None  # the vertices in the mesh file's frame (scaled)
    file_scale: np.ndarray | None = None  # the URDF's scale of the mesh


def check_plausibility(
    model: mujoco.MjModel,
    sources: dict[str, AssetSource] | None = None,
    skip: set[str] | None = None,
    robot: Robot | None = None,
) -> Plausibility:
    """Test every body of ``model`` with mass and geometry (except those named in ``skip``).

    ``sources``, the mesh products a build published the model's assets from (by asset file
    name), say which meshes came from DAE files tagged Y-up or X-up: only those can have a
    wrong up axis. Without them (a model mjcfbuild did not build) any mesh can. ``robot``,
    the URDF the model was built from, names the file and line of each mass finding and adds
    the links welded to the world (check.mass_findings)."""
    import mujoco

    from mjcfbuild.check.mass_findings import mass_findings

    result = Plausibility()
    geoms_of: dict[int, list[_Geom]] = {}
    for index in range(model.ngeom):
        if model.geom_type[index] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        geoms_of.setdefault(int(model.geom_bodyid[index]), []).append(_geom(model, index))
    robot_size = _robot_size(model)
    decisions = _up_axis_decisions(model, sources)
    tagged = None if decisions is None else set(decisions)
    for body, geoms in sorted(geoms_of.items()):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or f"body {body}"
        if body == 0 or model.body_mass[body] < MIN_MASS or name in (skip or set()):
            continue
        result.bodies += 1
        com = model.body_ipos[body].copy()
        problems = _oversized(geoms, robot_size) + _problems(geoms, com)
        if not problems:
            away = _turned_away(name, geoms, decisions or {})
            if away is not None:
                result.findings.append(away)
            continue
        turnable = [g for g in geoms if g.is_mesh and (tagged is None or g.name in tagged)]
        result.findings.append(_diagnose(name, geoms, com, problems, robot_size, turnable))
    # A body in mm is one finding, not a second one for the mass its huge mesh cannot fill.
    in_mm = {f.body for f in result.findings if f.cause == "units in mm"}
    for finding in mass_findings(model, robot, MIN_MASS, skip or set()):
        if in_mm and (finding.subject == "robot" or finding.body in in_mm):
            continue
        result.findings.append(finding)
    return result


def _up_axis_decisions(
    model: mujoco.MjModel, sources: dict[str, AssetSource] | None
) -> dict[str, UpAxisDecision] | None:
    """The meshes of ``model`` converted from a DAE file tagged Y_UP or X_UP, by mesh name,
    with what the build did with the tag (their product summary records it), or None when the
    model's meshes are not mjcfbuild products."""
    import json

    from mjcfbuild.meshes.upaxis import UpAxisDecision

    if not sources:
        return None
    tags: dict[Path, UpAxisDecision | None] = {}
    found: dict[str, UpAxisDecision] = {}
    raw = bytes(model.paths)
    for mesh in range(model.nmesh):
        start = int(model.mesh_pathadr[mesh])
        if start < 0:
            continue
        path = Path(raw[start : raw.index(b"\0", start)].decode())
        source = sources.get(path.name)
        for candidate in (path, source.product if source else None):
            if candidate is None:
                continue
            summary = candidate.parent.with_suffix(".json")
            if summary not in tags:
                try:
                    decision = json.loads(summary.read_text()).get("up_axis") or {}
                except (OSError, ValueError, AttributeError):
                    decision = {}
                tagged = decision.get("tag") in ("Y_UP", "X_UP")
                tags[summary] = UpAxisDecision.from_dict(decision) if tagged else None
            if (found_decision := tags[summary]) is not None:
                found[model.mesh(mesh).name] = found_decision
    return found


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
        scale = np.asarray(model.mesh_scale[mesh], float)
        points = local @ rotation.T + position
        return _Geom(mesh_name, visual, True, points, origin, axes, in_file, scale)
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


def _reference_size(mesh: _Geom, geoms: list[_Geom], robot_size: float) -> tuple[float, str]:
    """What ``mesh``'s size is compared with: the largest of its body's other geoms, else the
    robot's joint layout."""
    own = [d for g in geoms if g.name != mesh.name and (d := _diagonal(g.points)) > 0]
    if own:
        return max(own), "its body's other geometry"
    return robot_size, "the robot's joint layout"


def _millimetre_mesh(geoms: list[_Geom], robot_size: float) -> tuple[_Geom, float, str] | None:
    """A mesh hundreds of times larger than what it is compared with, and metres across: a
    mesh in mm (a problem itself: a robot whose meshes are all in mm keeps each centre of mass
    inside its huge mesh)."""
    for mesh in geoms:
        if not mesh.is_mesh:
            continue
        reference, what = _reference_size(mesh, geoms, robot_size)
        size = _diagonal(mesh.points)
        if reference > 1e-3 and size >= MM_RATIO * reference and size >= MM_SIZE:
            return mesh, size / reference, what
    return None


def _oversized(geoms: list[_Geom], robot_size: float) -> list[str]:
    found = _millimetre_mesh(geoms, robot_size)
    if found is None:
        return []
    mesh, ratio, what = found
    return [
        f"mesh '{mesh.name}' is {_diagonal(mesh.points):.3g} m across, {ratio:.0f} times {what}"
    ]


def _com_outside(points: list[np.ndarray], com: np.ndarray) -> float:
    """How far ``com`` lies outside the box of ``points``, beyond the margin (0: inside)."""
    import numpy as np

    everything = np.concatenate(points)
    low, high = everything.min(axis=0), everything.max(axis=0)
    outside = float(np.linalg.norm(np.maximum(low - com, 0) + np.maximum(com - high, 0)))
    allowed = COM_MARGIN * float(np.linalg.norm(high - low)) + COM_SLACK
    return outside if outside > allowed else 0.0


def _problems(geoms: list[_Geom], com: np.ndarray | None) -> list[str]:
    """What is wrong with ``geoms`` and the centre of mass ``com`` (None: the geometry only)."""
    import numpy as np

    problems = []
    visual = [g.points for g in geoms if g.visual]
    collision = [g.points for g in geoms if not g.visual]
    if com is not None:
        outside = _com_outside([g.points for g in geoms], com)
        if outside:
            problems.append(f"its centre of mass is {outside:.3g} m outside its geometry")
        elif visual and (outside := _com_outside(visual, com)):
            problems.append(f"its centre of mass is {outside:.3g} m outside its visual geometry")
    if visual and collision:
        shared = _shared_fraction(np.concatenate(visual), np.concatenate(collision))
        if shared < MIN_SHARED:
            problems.append(
                f"its visual and collision geometry barely overlap ({shared:.0%} of the "
                "smaller one's box)"
            )
    return problems


def _padded_boxes(a: np.ndarray, b: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The boxes of two point sets, padded a little, so a flat plate still has a volume."""
    import numpy as np

    boxes = []
    for points in (a, b):
        low, high = points.min(axis=0), points.max(axis=0)
        pad = 0.05 * float(np.max(high - low)) + 1e-4
        boxes.append((low - pad, high + pad))
    return boxes


def _iou(a: np.ndarray, b: np.ndarray) -> float:
    """The intersection over union of the two point sets' (padded) boxes."""
    import numpy as np

    (low_a, high_a), (low_b, high_b) = _padded_boxes(a, b)
    common = float(np.prod(np.clip(np.minimum(high_a, high_b) - np.maximum(low_a, low_b), 0, None)))
    union = float(np.prod(high_a - low_a) + np.prod(high_b - low_b)) - common
    return common / union if union > 0 else 0.0


def _shared_fraction(a: np.ndarray, b: np.ndarray) -> float:
    """How much of the smaller of the two point sets' boxes the other's box covers (boxes
    padded a little, so a flat plate still has a volume)."""
    import numpy as np

    (low_a, high_a), (low_b, high_b) = _padded_boxes(a, b)
    common = np.clip(np.minimum(high_a, high_b) - np.maximum(low_a, low_b), 0, None)
    smaller = min(float(np.prod(high_a - low_a)), float(np.prod(high_b - low_b)))
    return float(np.prod(common)) / smaller if smaller > 0 else 1.0


def _diagnose(
    body: str,
    geoms: list[_Geom],
    com: np.ndarray,
    problems: list[str],
    robot_size: float,
    turnable: list[_Geom],
) -> BodyFinding:
    found = _millimetre_mesh(geoms, robot_size)
    if found is not None:
        mesh, ratio, what = found
        return BodyFinding(
            body,
            problems,
            "units in mm",
            f"units in mm: mesh '{mesh.name}' is about {ratio:.0f} times {what}; scale it by "
            '0.001 (<mesh scale="0.001 0.001 0.001"/> in the URDF) or export it in metres',
            True,
        )
    visual = [g.points for g in geoms if g.visual]
    collision = [g.points for g in geoms if not g.visual]
    as_read = _collision_fit(turnable, geoms)
    for label, turn in _QUARTER_TURNS:
        trial = [_turned(g, turn) if g in turnable else g for g in geoms]
        if not turnable or _problems(trial, com):
            continue
        # The centre of mass fits the turned mesh; its collision geometry must agree.
        turned_fit = _collision_fit([g for g in trial if g.is_mesh and g not in geoms], geoms)
        if as_read is None or (turned_fit is not None and turned_fit > as_read + CLEARER):
            names = ", ".join(sorted({f"'{m.name}'" for m in turnable}))
            return BodyFinding(
                body,
                problems,
                "up axis",
                f"up axis: mesh {names} fits once turned {label}; set "
                "meshes.collada_up_axis_files for its DAE file in robot.yaml (apply or "
                "ignore)",
                False,
            )
    # Visual and collision geometry, authored apart, agree, and the centre of mass is outside
    # both: the inertial is what is off, not a mesh.
    agree = bool(visual and collision) and not _problems(geoms, None)
    if agree and _com_outside(collision, com) and _com_outside(visual, com):
        return BodyFinding(
            body,
            problems,
            "wrong origin",
            "a wrong inertial <origin>: the body's visual and collision geometry agree with "
            "each other, its centre of mass is elsewhere",
            False,
        )
    return BodyFinding(
        body,
        problems,
        "wrong origin",
        "a wrong origin: check the <origin> of its visual, collision and inertial elements, "
        "and the mesh files' own origins",
        False,
    )


def _collision_fit(meshes: list[_Geom], geoms: list[_Geom]) -> float | None:
    """How well ``meshes`` overlap the body's collision geometry that is not among them (the
    intersection over union of the two boxes), or None when there is none to compare with."""
    import numpy as np

    own = {g.name for g in meshes}
    others = [g.points for g in geoms if not g.visual and g.name not in own]
    if not meshes or not others:
        return None
    return _iou(np.concatenate([g.points for g in meshes]), np.concatenate(others))


def _turned_away(
    body: str, geoms: list[_Geom], decisions: dict[str, UpAxisDecision]
) -> BodyFinding | None:
    """A finding for a body whose meshes the build turned to Z-up (as their DAE files' tag
    says) while, as written, they fit the body's own collision geometry far better."""
    from mjcfbuild.meshes.upaxis import up_rotation

    turned = [g for g in geoms if g.is_mesh and (d := decisions.get(g.name)) and d.turned]
    tags = {decisions[g.name].tag for g in turned}
    if len(tags) != 1:
        return None
    (tag,) = tags
    back = [list(row) for row in zip(*up_rotation(tag), strict=True)]  # its inverse
    as_built = _collision_fit(turned, geoms)
    as_written = _collision_fit([_turned(g, back) for g in turned], geoms)
    if as_built is None or as_written is None:
        return None
    if as_written < AWAY_FIT or as_built > AWAY_RATIO * as_written:
        return None
    names = ", ".join(sorted({f"'{g.name}'" for g in turned}))
    return BodyFinding(
        body,
        [
            f"mesh {names}, turned to Z-up as its DAE file's {tag} tag says, overlaps the "
            f"body's collision geometry {as_built:.2f} (intersection over union), "
            f"{as_written:.2f} as written"
        ],
        "up axis",
        f"up axis: the data of mesh {names} is Z-up already; set "
        "meshes.collada_up_axis_files for its DAE file to ignore in robot.yaml",
        False,
    )


def _turned(geom: _Geom, turn: list[list[int]] | list[list[float]]) -> _Geom:
    """``geom``'s mesh turned about its file's own origin (``turn`` is a turn of the file's
    unscaled data, so a scaled mesh is unscaled first)."""
    import numpy as np

    assert geom.file_points is not None and geom.file_axes is not None
    assert geom.file_origin is not None
    rotation = np.asarray(turn, float)
    if geom.file_scale is not None and np.all(geom.file_scale != 0):
        rotation = (rotation * geom.file_scale[:, None]) / geom.file_scale[None, :]
    moved = (geom.file_points @ rotation.T) @ geom.file_axes.T + geom.file_origin
    return _Geom(geom.name, geom.visual, True, moved)


_QUARTER_TURNS = [
    ("a quarter turn about x (Y-up data read as Z-up)", [[1, 0, 0], [0, 0, -1], [0, 1, 0]]),
    ("a quarter turn back about x (Z-up data turned as Y-up)", [[1, 0, 0], [0, 0, 1], [0, -1, 0]]),
    ("a quarter turn about y (X-up data read as Z-up)", [[0, 0, -1], [0, 1, 0], [1, 0, 0]]),
    ("a quarter turn back about y", [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]),
]
