"""The training variant of a built model, made with MjSpec from the model file.

Each link's collision geometry becomes one primitive fitted to it (the ``primitive`` policy's
fit, :func:`mjcfbuild.collision.primitives.fit_primitive`): the smallest enclosing capsule or
sphere, or box where a box is less than 70% of that (a flat trunk), and only a sphere or capsule
for the links that meet the floor (sphere- and capsule-plane contacts are the cheapest). Where
the shape is more than ``primitive_fit`` times the volume of the geometry's convex hull (an
L-shaped bracket), the hull itself is used, cut down to ``max_hull_vertices`` vertices. A link
whose geometry is already one sphere or capsule, or any primitives on a link that meets the
floor (a foot's spheres), keeps it; other primitives are refitted like meshes. Cylinders
become capsules: MuJoCo Warp collides cylinders (and box against box) through its general
convex solver, and MJX has no cylinder-mesh collision; capsules, spheres and box-capsule
pairs have closed-form collisions.

Visual meshes stay, with contype and conaffinity 0. Contacts follow
:mod:`mjcfbuild.training.contacts`, in contype/conaffinity bits and ``<exclude>``s: floor links
get conaffinity bit 1 (the floor's contype is 1), links in self pairs get bit 2 in both, every
other geom 0/0, and every pair of bit-2 bodies that is not a self pair is excluded. The engine
then considers exactly the pairs the rules name, and its broad phase (bounding volumes) drops
most of them before the narrow phase at each step. Explicit ``<pair>``s would name the same
set, but MuJoCo Warp runs the narrow phase on every explicit pair at every step: on g1's 199
self pairs that made the variant slower than the full model (measured on the CPU).

Joints lose their ``frictionloss`` unless told to keep it: dry friction is a constraint row
per joint that the solver iterates on in every world at every step. ``<dcmotor>`` servos
become ``<position>`` servos with the same gains unless told to stay (MJX refuses
``<dcmotor>``). The solver settings are the device's (:mod:`mjcfbuild.training.solver`).

Fitted primitives enclose the geometry, so they reach a little lower than it: a floating robot
is raised by that much (its body and its keyframes) so it starts on the floor, not in it.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

from mjcfbuild.actuators import as_position_servos
from mjcfbuild.errors import ManifestError
from mjcfbuild.training.contacts import floor_bodies, self_pairs
from mjcfbuild.training.solver import solver_settings

FLOOR_CONTACT = 2e-3  # m: collision geometry this close to the floor at home touches it
SOLE = 5e-3  # m: a touching link's geoms this close to its lowest point at home are its sole
SELF_BIT = 2  # contype/conaffinity bit of the geoms in self pairs (the floor's is 1)
BOX_PREFERENCE = 0.7  # a box replaces a capsule only when it is less than this share of it


@dataclass(frozen=True)
class VariantSettings:
    """How the variant is made (robot.yaml ``output.training``)."""

    floor_add: tuple[str, ...] = ()
    floor_remove: tuple[str, ...] = ()
    self_contacts: bool = False
    max_hull_vertices: int = 16
    primitive_fit: float = 2.0
    device: str = "gpu"  # gpu or cpu: picks the solver defaults (mjcfbuild.training.solver)
    iterations: int | None = None  # None: the solver's default
    ls_iterations: int | None = None
    solver: str | None = None  # MuJoCo's name, lower case: cg or newton; None: the device's
    timestep: float | None = None
    frictionloss: bool = False
    dcmotor: bool = False
    label: str = "robot.yaml output.training"  # where the settings are, for messages


@dataclass
class Variant:
    """The variant's MJCF and what was done to make it."""

    xml: str
    geoms: dict[str, list[str]] = field(default_factory=dict)  # body -> its collision kinds
    floor: list[str] = field(default_factory=list)
    pairs: list[tuple[str, str]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    raised: float = 0.0
    solver: dict[str, Any] = field(default_factory=dict)  # device, solver and iteration caps

    def to_dict(self) -> dict[str, Any]:
        """The report of the variant, JSON-ready."""
        return {
            "geoms": self.geoms,
            "floor": self.floor,
            "pairs": [list(pair) for pair in self.pairs],
            "notes": self.notes,
            "raised": self.raised,
            "solver": self.solver,
        }


def build_variant(model_path: str, verdicts: list[dict], settings: VariantSettings) -> Variant:
    """The training variant of the model at ``model_path``, given the collision matrix's
    ``verdicts`` (empty without a matrix)."""
    import mujoco

    spec = mujoco.MjSpec.from_file(model_path)
    model = spec.compile()
    data = _at_home(model)
    names = _body_names(model)
    parents = {
        names[b]: (names[model.body_parentid[b]] if model.body_parentid[b] else None)
        for b in range(1, model.nbody)
    }
    colliding_geoms = [
        g for g in range(model.ngeom) if model.geom_contype[g] or model.geom_conaffinity[g]
    ]
    by_body: dict[str, list[int]] = {}
    for geom in colliding_geoms:
        by_body.setdefault(names[model.geom_bodyid[geom]], []).append(geom)
    add = [
        _body_of(model, spec, link, f"{settings.label}.floor_contacts.add")
        for link in settings.floor_add
    ]
    remove = [
        _body_of(model, spec, link, f"{settings.label}.floor_contacts.remove")
        for link in settings.floor_remove
    ]
    lowest_full, touching = _touching(model, data, colliding_geoms, names)
    floor = floor_bodies(parents, by_body, touching, add, remove)
    pairs = self_pairs(verdicts, parents, by_body) if settings.self_contacts else []

    variant = Variant(xml="", floor=floor, pairs=pairs)
    spec_geoms = {model.bind(g).id: g for g in spec.geoms}
    new_names: dict[str, list[str]] = {}
    for body, geoms in sorted(by_body.items()):
        template = spec_geoms[geoms[0]]
        shapes = _shapes(model, geoms, body in floor, settings, variant)
        for geom in geoms:
            spec.delete(spec_geoms[geom])
        new_names[body] = []
        for index, shape in enumerate(shapes):
            name = f"{body}_collision" + (f"_{index}" if len(shapes) > 1 else "")
            _add_geom(spec, spec.body(body), template, shape, name, body in floor)
            new_names[body].append(name)
        variant.geoms[body] = [shape.kind for shape in shapes]
    for exclude in list(spec.excludes):
        spec.delete(exclude)  # the full model's; the variant's own follow
    colliding_bodies = sorted({body for pair in pairs for body in pair})
    for body in colliding_bodies:
        for name in new_names[body]:
            geom = spec.geom(name)
            geom.contype |= SELF_BIT
            geom.conaffinity |= SELF_BIT
    _soles_only(spec, sorted(set(floor) & touching), new_names)
    variant.pairs = _apart_at_home(spec, pairs, variant)
    wanted = set(variant.pairs)
    for index, first in enumerate(colliding_bodies):
        for second in colliding_bodies[index + 1 :]:
            if (first, second) not in wanted:
                spec.add_exclude(bodyname1=first, bodyname2=second)
    _drop_unused_meshes(spec)
    if not settings.frictionloss:
        _drop_frictionloss(spec, variant)
    if not settings.dcmotor:
        _position_servos(spec, variant)
    solver = solver_settings(
        settings.device, settings.solver, settings.iterations, settings.ls_iterations
    )
    spec.option.iterations = solver.iterations
    spec.option.ls_iterations = solver.ls_iterations
    spec.option.solver = getattr(mujoco.mjtSolver, f"mjSOL_{solver.solver.upper()}")
    variant.solver = {"device": settings.device, **asdict(solver)}
    if settings.timestep is not None:
        spec.option.timestep = settings.timestep
    variant.raised = _onto_floor(spec, lowest_full)
    variant.xml = spec.to_xml()
    return variant


@dataclass(frozen=True)
class Shape:
    """One collision geom of the variant, in its body's frame."""

    kind: str  # sphere, capsule, box or mesh
    size: tuple[float, ...] = ()
    pos: tuple[float, float, float] = (0.0, 0.0, 0.0)
    quat: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)
    vertices: tuple[float, ...] = ()  # a capped hull's, for kind mesh


def _at_home(model):
    import mujoco

    data = mujoco.MjData(model)
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if home >= 0:
        mujoco.mj_resetDataKeyframe(model, data, home)
    mujoco.mj_forward(model, data)
    return data


def _body_names(model) -> list[str]:
    import mujoco

    return [
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or f"body{b}"
        for b in range(model.nbody)
    ]


def _body_of(model, spec, link: str, where: str) -> str:
    """The body a link became: its own, or the one it was fused into (which holds its site)."""
    import mujoco

    if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, link) >= 0:
        return link
    site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, link)
    if site >= 0:
        body = model.site_bodyid[site]
        return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body)
    raise ManifestError(f"link '{link}' is not a link of the robot", file=where)


def _touching(model, data, geoms: list[int], names: list[str]) -> tuple[float, set[str]]:
    """The lowest collision point at home, and the bodies within FLOOR_CONTACT of the floor."""
    from mjcfbuild.control.floor import geom_lowest_points

    points = geom_lowest_points(model, data)
    if not points:
        return 0.0, set()
    lowest = min(float(point[2]) for point in points.values())
    floor = min(lowest, 0.0)
    touching = {
        names[model.geom_bodyid[g]]
        for g, point in points.items()
        if g in geoms and point[2] <= floor + FLOOR_CONTACT
    }
    return lowest, touching


def _shapes(model, geoms: list[int], on_floor: bool, settings: VariantSettings, variant: Variant):
    """The collision shapes that replace ``geoms`` (one body's)."""
    import mujoco

    from mjcfbuild.collision.primitives import fit_primitive

    types = mujoco.mjtGeom
    authored = all(model.geom_type[g] != types.mjGEOM_MESH for g in geoms)
    round_ = (types.mjGEOM_SPHERE, types.mjGEOM_CAPSULE)
    if authored and (on_floor or (len(geoms) == 1 and model.geom_type[geoms[0]] in round_)):
        # A foot's own spheres or boxes are what it stands on; a sphere or capsule is already
        # the cheapest shape. A box elsewhere is refitted: a capsule where it is slender.
        return [_kept(model, g, variant) for g in geoms]
    points = _points(model, geoms)
    primitive = fit_primitive(points, ("sphere", "capsule"))
    if not on_floor:
        box = fit_primitive(points, ("box",))
        if box.volume < BOX_PREFERENCE * primitive.volume:
            primitive = box
    hull_volume, hull_points = _hull(points, settings.max_hull_vertices)
    if primitive.volume <= settings.primitive_fit * hull_volume:
        quat = _quat(primitive.transform[:3, :3])
        pos = tuple(float(v) for v in primitive.transform[:3, 3])
        size = tuple(float(s) for s in primitive.size)
        return [Shape(primitive.kind, size, pos, quat)]  # type: ignore[arg-type]
    if authored:  # several primitives no single one fits: they stay (cylinders as capsules)
        return [_kept(model, g, variant) for g in geoms]
    return [Shape("mesh", vertices=tuple(float(v) for v in hull_points.ravel()))]


def _kept(model, geom: int, variant: Variant) -> Shape:
    """An authored primitive as it is; a cylinder as the capsule of its radius and length."""
    import mujoco

    kind = mujoco.mjtGeom(model.geom_type[geom]).name.removeprefix("mjGEOM_").lower()
    size = tuple(float(s) for s in model.geom_size[geom])
    pos = tuple(float(v) for v in model.geom_pos[geom])
    quat = tuple(float(v) for v in model.geom_quat[geom])
    if kind == "cylinder":
        kind = "capsule"
        body = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[geom])
        variant.notes.append(f"{body}: cylinder replaced by a capsule")
    sizes = {"sphere": 1, "capsule": 2, "box": 3, "ellipsoid": 3}
    return Shape(kind, size[: sizes.get(kind, 3)], pos, quat)  # type: ignore[arg-type]


def _points(model, geoms: list[int]):
    """Points of the geoms' surfaces in their body's frame: mesh vertices, primitives'
    extreme points."""
    import mujoco
    import numpy as np

    types = mujoco.mjtGeom
    found = []
    for geom in geoms:
        flat = np.zeros(9)
        mujoco.mju_quat2Mat(flat, model.geom_quat[geom])
        rotation = flat.reshape(3, 3)
        kind, size = model.geom_type[geom], model.geom_size[geom]
        if kind == types.mjGEOM_MESH:
            mesh = model.geom_dataid[geom]
            start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
            local = model.mesh_vert[start : start + count].astype(np.float64)
        else:
            local = _primitive_points(kind, size)
        found.append(local @ rotation.T + model.geom_pos[geom])
    return np.concatenate(found)


def _primitive_points(kind: int, size):
    """Points on a primitive's surface that its enclosing shapes must contain."""
    import itertools
    import math

    import mujoco
    import numpy as np

    types = mujoco.mjtGeom
    ring = [
        (math.cos(2 * math.pi * k / 16), math.sin(2 * math.pi * k / 16), 0.0) for k in range(16)
    ]
    if kind == types.mjGEOM_BOX:
        return np.array(list(itertools.product(*[(-s, s) for s in size])))
    if kind == types.mjGEOM_SPHERE:
        sphere = [*ring, (0, 0, 1), (0, 0, -1), *[(x, 0, y) for x, y, _ in ring]]
        return np.array(sphere) * size[0]
    if kind == types.mjGEOM_ELLIPSOID:
        sphere = [*ring, (0, 0, 1), (0, 0, -1), *[(x, 0, y) for x, y, _ in ring]]
        return np.array(sphere) * np.asarray(size[:3])
    radius, half = size[0], size[1]
    circle = np.array(ring) * radius
    shift = np.array([0.0, 0.0, half])
    ends = [circle + shift, circle - shift]
    if kind == types.mjGEOM_CAPSULE:
        ends.append(np.array([(0, 0, half + radius), (0, 0, -half - radius)]))
    return np.concatenate(ends)


def _hull(points, cap: int):
    """The convex hull's volume, and at most ``cap`` of its vertices: the ones farthest apart
    (farthest-point sampling from the vertex farthest from the centroid; deterministic)."""
    import numpy as np
    from scipy.spatial import ConvexHull

    hull = ConvexHull(points)
    vertices = points[np.sort(hull.vertices)]
    if len(vertices) <= cap:
        return float(hull.volume), vertices
    centroid = vertices.mean(axis=0)
    chosen = [int(np.argmax(np.linalg.norm(vertices - centroid, axis=1)))]
    distance = np.linalg.norm(vertices - vertices[chosen[0]], axis=1)
    while len(chosen) < cap:
        pick = int(np.argmax(distance))
        chosen.append(pick)
        distance = np.minimum(distance, np.linalg.norm(vertices - vertices[pick], axis=1))
    return float(hull.volume), vertices[sorted(chosen)]


def _quat(rotation) -> tuple[float, float, float, float]:
    import mujoco
    import numpy as np

    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.ascontiguousarray(rotation, dtype=np.float64).ravel())
    if quat[0] < 0:
        quat = -quat
    return (float(quat[0]), float(quat[1]), float(quat[2]), float(quat[3]))


def _add_geom(spec, body, template, shape: Shape, name: str, on_floor: bool) -> None:
    """Add ``shape`` to ``body``, with the contact settings of ``template`` (a geom it replaces)."""
    import mujoco

    kinds = {
        "sphere": mujoco.mjtGeom.mjGEOM_SPHERE,
        "capsule": mujoco.mjtGeom.mjGEOM_CAPSULE,
        "box": mujoco.mjtGeom.mjGEOM_BOX,
        "ellipsoid": mujoco.mjtGeom.mjGEOM_ELLIPSOID,
        "mesh": mujoco.mjtGeom.mjGEOM_MESH,
    }
    geom = body.add_geom(name=name, type=kinds[shape.kind])
    if shape.kind == "mesh":
        mesh = spec.add_mesh(name=f"{name}_hull")
        mesh.uservert = list(shape.vertices)
        geom.meshname = mesh.name
    else:
        size = list(shape.size) + [0.0] * (3 - len(shape.size))
        geom.size = size
        geom.pos = list(shape.pos)
        geom.quat = list(shape.quat)
    for attribute in ("group", "friction", "condim", "solref", "solimp", "priority", "margin"):
        setattr(geom, attribute, getattr(template, attribute))
    geom.rgba = template.rgba
    geom.contype = 0
    geom.conaffinity = 1 if on_floor else 0


def _soles_only(spec, touching: list[str], new_names: dict[str, list[str]]) -> None:
    """Of a link that stands on the floor at home, only the geoms that reach within SOLE of
    its lowest point keep the floor: go1's foot sphere does, the box along its shin (13 mm
    higher) does not; each floor geom is one more contact the solver works on when the leg
    tilts."""
    from mjcfbuild.control.floor import geom_lowest_points

    model = spec.compile()
    data = _at_home(model)
    points = geom_lowest_points(model, data)
    for body in touching:
        heights = {}
        for name in new_names.get(body, []):
            geom = model.geom(name).id
            if geom in points:
                heights[name] = float(points[geom][2])
        if not heights:
            continue
        lowest = min(heights.values())
        for name, height in heights.items():
            if height > lowest + SOLE:
                spec.geom(name).conaffinity &= ~1


def _apart_at_home(spec, pairs: list[tuple[str, str]], variant: Variant) -> list[tuple[str, str]]:
    """The body pairs whose new geoms do not touch at home, with a note for each other one.

    Enclosing shapes are larger than the geometry they replace, so two links that were apart
    at home can overlap in the variant (go1's trunk capsule and its thighs): a contact held
    from the first step fights the servos, which is why the matrix excludes pairs touching at
    home in the first place.
    """
    model = spec.compile()
    data = _at_home(model)
    names = _body_names(model)
    touching = set()
    for contact in data.contact[: data.ncon]:
        if contact.dist < 0:
            first = names[model.geom_bodyid[contact.geom1]]
            second = names[model.geom_bodyid[contact.geom2]]
            touching.add((min(first, second), max(first, second)))
    for first, second in pairs:
        if (first, second) in touching:
            variant.notes.append(f"{first} and {second} overlap at home in the variant: no pair")
    return [pair for pair in pairs if pair not in touching]


def _drop_frictionloss(spec, variant: Variant) -> None:
    """Joints without dry friction: each joint with frictionloss is a constraint row the
    solver works on at every step of every world (on go1 in MuJoCo Warp, 12 of them cost
    as much as the rest of the step)."""
    joints = [joint for joint in spec.joints if joint.frictionloss > 0]
    for joint in joints:
        joint.frictionloss = 0.0
    if joints:
        variant.notes.append(
            f"frictionloss removed from {len(joints)} joints (output.training.frictionloss)"
        )


def _position_servos(spec, variant: Variant) -> None:
    """``<dcmotor input="pos">`` servos as ``<position>`` servos with the same gains
    (:func:`mjcfbuild.actuators.as_position_servos`): MJX's JAX engine refuses ``<dcmotor>``,
    and training set-ups drive joints with position servos (MuJoCo Menagerie's MJX variants,
    mjlab)."""
    turned, kept = as_position_servos(spec)
    if turned:
        variant.notes.append(
            f"{turned} <dcmotor> servos are <position> servos with the same gains and force "
            "limits, without their torque-speed lines (MJX has no <dcmotor>; "
            "output.training.dcmotor keeps them for MuJoCo Warp)"
        )
    if kept:
        # Voltage or velocity input, or an integral term: no position servo is the same drive.
        variant.notes.append(
            f"{len(kept)} <dcmotor> actuators kept as they are ({', '.join(kept[:4])}): they are "
            "not position servos without an integral term, so no <position> servo matches them; "
            "MuJoCo Warp runs them, MJX refuses them"
        )


def _drop_unused_meshes(spec) -> None:
    used = {geom.meshname for geom in spec.geoms if geom.meshname}
    for mesh in list(spec.meshes):
        if mesh.name not in used:
            spec.delete(mesh)


def _onto_floor(spec, lowest_full: float) -> float:
    """Raise a floating robot so its new geometry's lowest point at home is the old one's;
    the distance raised (0 for a fixed robot)."""
    import mujoco

    model = spec.compile()
    data = _at_home(model)
    from mjcfbuild.control.floor import geom_lowest_points

    points = geom_lowest_points(model, data)
    roots = [j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
    if not points or not roots:
        return 0.0
    lift = lowest_full - min(float(point[2]) for point in points.values())
    if lift <= 1e-9:
        return 0.0
    names = _body_names(model)
    for joint in roots:
        body = spec.body(names[model.jnt_bodyid[joint]])
        body.pos = [body.pos[0], body.pos[1], body.pos[2] + lift]
        address = model.jnt_qposadr[joint] + 2
        for key in spec.keys:
            if len(key.qpos) == model.nq:
                qpos = list(key.qpos)
                qpos[address] += lift
                key.qpos = qpos
    return lift
