"""Writing a :class:`ModelOut` as URDF: links from bodies, joints, geometry, frames, mimics.

How MuJoCo's concepts map onto URDF's (also in docs/export_urdf.md):

- Every body is a link named like the body, with its mass, centre of mass and full inertia
  tensor (in axes parallel to the link's).
- A body's joints become URDF joints of the same names. One joint at the body's origin joins
  the parent link to the body's link directly. Several joints (or one away from the origin)
  form a chain of massless links, one per joint, each at its joint's anchor, and a fixed joint
  brings the chain back to the body's own frame, so every link keeps its body's pose.
- hinge: revolute if limited, else continuous. slide: prismatic; URDF needs limits, so an
  unlimited slide gets +/- ``UNLIMITED_SLIDE``. ball: three revolute joints about the body's
  x, y and z axes (``<name>_x``, ``_y``, ``_z``). free: the body floats. If it is the only body
  at the top, it becomes the URDF's root (a URDF describes a floating robot by its base);
  otherwise a ``floating`` joint attaches it to the ``world`` link.
- A body without joints hangs on a fixed joint.
- Joint couplings (``<equality><joint>`` with a linear polynomial) become ``<mimic>``.
- Geoms: box, sphere and cylinder as URDF primitives; a capsule as a cylinder and two spheres
  (the same shape exactly); ellipsoids and meshes as OBJ files. Visual and collision are told
  apart by class name, then contype/conaffinity, then group (3 and up: collision only).
- Sites become links on fixed joints, so sensor frames survive; a site named like its body at
  the body's origin (the frame marker mjcfbuild writes for every link) is that link itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from mjcfbuild.export.meshfiles import MeshFiles, colour_key, colour_text
from mjcfbuild.export.model import BodyOut, GeomOut, JointOut, ModelOut
from mjcfbuild.markup import xml_attribute
from mjcfbuild.numbers import output_list
from mjcfbuild.urdf.model import WORLD
from mjcfbuild.urdf.transforms import Transform, vec3

UNLIMITED_SLIDE = 1000.0
BALL_AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}
ELLIPSOID_SEGMENTS = 24


@dataclass
class ExportOptions:
    """How the URDF refers to its mesh files, and whether sites become frame links."""

    asset_prefix: str = "meshes/"
    sites: bool = True
    header: str | None = None


@dataclass
class ExportResult:
    """The URDF text, its mesh files by name, and what could not be carried over."""

    urdf: bytes
    meshes: dict[str, bytes]
    warnings: list[str] = field(default_factory=list)


@dataclass
class _Joint:
    name: str
    kind: str
    parent: str
    child: str
    origin: Transform
    axis: tuple[float, float, float] | None = None
    limit: tuple[float | None, float | None, float] | None = None
    damping: float = 0.0
    friction: float = 0.0
    mimic: tuple[str, float, float] | None = None
    velocity: float | None = None  # None: unknown, written as 0 (URDF requires a value)


class _Names:
    """Unique names: the wanted one if free, else with a number appended."""

    def __init__(self) -> None:
        self.taken: set[str] = set()

    def claim(self, wanted: str) -> str:
        name, number = wanted, 2
        while name in self.taken:
            name, number = f"{wanted}_{number}", number + 1
        self.taken.add(name)
        return name


def write_urdf(model: ModelOut, options: ExportOptions) -> ExportResult:
    """The URDF of ``model`` and the mesh files it refers to."""
    warnings = list(model.warnings)
    link_names, joint_names = _Names(), _Names()
    links = {body.name: link_names.claim(body.name) for body in model.bodies}
    for body in model.bodies:  # joint names come from the model and are kept as they are
        for model_joint in body.joints:
            if model_joint.kind in ("hinge", "slide", "free"):
                joint_names.claim(model_joint.name)
    root = _root(model, options)
    joints: list[_Joint] = []
    extra_links: list[str] = []
    for body in model.bodies:
        if body.parent is None or body.name == root:
            continue
        joints += _body_joints(body, links, link_names, joint_names, extra_links, warnings)
    mimics = {m.follower: (m.leader, m.multiplier, m.offset) for m in model.mimics}
    single = {j.name for j in joints if j.kind in ("revolute", "continuous", "prismatic")}
    for joint in joints:
        mimic = mimics.get(joint.name)
        if mimic is not None and mimic[0] in single:
            joint.mimic = mimic
    unknown = [j.name for j in joints if j.limit is not None and j.velocity is None]
    if unknown:
        listed = ", ".join(unknown[:5]) + (
            f" and {len(unknown) - 5} more" if len(unknown) > 5 else ""
        )
        warnings.append(
            f"no speed limit known for {len(unknown)} joint(s) ({listed}): written as "
            "velocity=\"0\", which MoveIt reads as 'cannot move'; set them in MoveIt's "
            "joint_limits.yaml (or drive the joints with a <dcmotor> or a velocity servo)"
        )
    frames: list[str] = []
    if options.sites:
        for body in model.bodies:
            if body.parent is None and root != WORLD:
                continue
            for name, pose in body.sites:
                if name == body.name and _near_identity(pose):
                    continue  # the body's own frame marker
                frame = link_names.claim(name)
                frames.append(frame)
                name = joint_names.claim(f"{frame}_joint")
                joints.append(_Joint(name, "fixed", links[body.name], frame, pose))
    files = MeshFiles(model.meshes)
    bodies = [b for b in model.bodies if b.parent is not None or root == WORLD]
    body_lines = {b.name: _link_lines(b, links[b.name], files, options, warnings) for b in bodies}
    stems = files.stems()
    lines = ['<?xml version="1.0" encoding="utf-8"?>']
    if options.header:
        lines.append(f"<!-- {options.header} -->")
    lines.append(f"<robot name={xml_attribute(model.name)}>")
    for colour in sorted(files.colours):
        rgba = files.colours[colour]
        lines.append(
            f'  <material name="color_{colour}"><color rgba="{colour_text(rgba)}"/></material>'
        )
    for body in bodies:
        lines += body_lines[body.name]
    for name in extra_links + frames:
        lines.append(f"  <link name={xml_attribute(name)}/>")
    for joint in joints:
        lines += _joint_lines(joint)
    lines.append("</robot>")
    text = "\n".join(lines) + "\n"
    for (mesh, key), stem in stems.items():
        token = f"@MESH:{mesh}:{key or ''}@"
        text = text.replace(token, f"{options.asset_prefix}{stem}.obj")
    return ExportResult(text.encode("utf-8"), files.files(), warnings)


def _root(model: ModelOut, options: ExportOptions) -> str:
    """The root link: the world, or the one top-level body when the world holds nothing."""
    world = model.bodies[0]
    top = [b for b in model.bodies if b.parent == world.name]
    world_sites = options.sites and bool(world.sites)
    if world.geoms or world_sites or len(top) != 1:
        return WORLD
    joints = top[0].joints
    if not joints or (len(joints) == 1 and joints[0].kind == "free"):
        return top[0].name
    return WORLD


def _body_joints(
    body: BodyOut,
    links: dict[str, str],
    link_names: _Names,
    joint_names: _Names,
    extra_links: list[str],
    warnings: list[str],
) -> list[_Joint]:
    assert body.parent is not None, "called only for a child body"
    parent, child = links[body.parent], links[body.name]
    steps = _steps(body, joint_names, warnings)
    if not steps:
        return [_Joint(joint_names.claim(f"{child}_joint"), "fixed", parent, child, body.pose)]
    if steps[0].kind == "floating":
        steps[0].parent, steps[0].child, steps[0].origin = parent, child, body.pose
        return steps
    result = []
    previous_link, previous_anchor = parent, None
    for index, step in enumerate(steps):
        anchor = step.origin.position
        last = index == len(steps) - 1
        at_origin = all(abs(v) < 1e-12 for v in anchor)
        step.parent = previous_link
        step.child = child if last and at_origin else link_names.claim(f"{child}_{step.name}")
        if step.child != child:
            extra_links.append(step.child)
        if previous_anchor is None:
            step.origin = body.pose.compose(Transform(position=anchor))
        else:
            step.origin = Transform(position=_minus(anchor, previous_anchor))
        result.append(step)
        previous_link, previous_anchor = step.child, anchor
    if previous_link != child:
        assert previous_anchor is not None, "set by the steps, of which there is one or more"
        back = Transform(position=vec3(-v for v in previous_anchor))
        result.append(
            _Joint(joint_names.claim(f"{child}_joint"), "fixed", previous_link, child, back)
        )
    return result


def _steps(body: BodyOut, joint_names: _Names, warnings: list[str]) -> list[_Joint]:
    """The URDF joints of a body's MuJoCo joints, in order; origin holds the anchor for now."""
    steps = []
    for joint in body.joints:
        anchor = Transform(position=joint.position)
        if joint.kind == "free":
            steps.append(_Joint(joint.name, "floating", "", "", anchor))
        elif joint.kind == "hinge":
            limit: tuple[float | None, float | None, float] | None = (
                (joint.lower, joint.upper, joint.effort) if joint.limited else None
            )
            kind = "revolute" if joint.limited else "continuous"
            if not joint.limited and (joint.effort > 0 or joint.velocity is not None):
                limit = (None, None, joint.effort)
            steps.append(_moving(joint, kind, anchor, limit))
        elif joint.kind == "slide":
            lower, upper = joint.lower, joint.upper
            if not joint.limited:
                lower, upper = -UNLIMITED_SLIDE, UNLIMITED_SLIDE
                warnings.append(
                    f"slide joint '{joint.name}' has no range; URDF needs one, so it got "
                    f"+/-{UNLIMITED_SLIDE:g} m"
                )
            steps.append(_moving(joint, "prismatic", anchor, (lower, upper, joint.effort)))
        else:  # ball
            bound = joint.upper if joint.limited else None
            for suffix, axis in BALL_AXES.items():
                limit = (-bound, bound, joint.effort) if bound is not None else None
                name = joint_names.claim(f"{joint.name}_{suffix}")
                kind = "revolute" if bound is not None else "continuous"
                steps.append(_Joint(name, kind, "", "", anchor, axis, limit))
            warnings.append(
                f"ball joint '{joint.name}' became three revolute joints about x, y and z"
            )
    return steps


def _moving(joint: JointOut, kind: str, anchor: Transform, limit) -> _Joint:
    return _Joint(
        joint.name,
        kind,
        "",
        "",
        anchor,
        joint.axis,
        limit,
        damping=joint.damping,
        friction=joint.friction,
        velocity=joint.velocity,
    )


def _link_lines(
    body: BodyOut, name: str, files: MeshFiles, options: ExportOptions, warnings: list[str]
) -> list[str]:
    lines = [f"  <link name={xml_attribute(name)}>"]
    if body.mass > 0:
        i = body.inertia
        lines += [
            "    <inertial>",
            f'      <origin xyz="{output_list(body.com)}" rpy="0 0 0"/>',
            f'      <mass value="{output_list([body.mass])}"/>',
            f'      <inertia ixx="{_n(i[0][0])}" ixy="{_n(i[0][1])}" ixz="{_n(i[0][2])}" '
            f'iyy="{_n(i[1][1])}" iyz="{_n(i[1][2])}" izz="{_n(i[2][2])}"/>',
            "    </inertial>",
        ]
    for role in ("visual", "collision"):
        for geom in body.geoms:
            if role in geom.roles:
                lines += _geom_lines(geom, role, files)
    if len(lines) == 1:
        return [f"  <link name={xml_attribute(name)}/>"]
    lines.append("  </link>")
    return lines


def _geom_lines(geom: GeomOut, role: str, files: MeshFiles) -> list[str]:
    """One ``<visual>`` or ``<collision>`` (two more spheres for a capsule)."""
    material = ""
    if role == "visual":
        material = f'<material name="color_{files.colour(geom.rgba)}"/>'
    shapes: list[tuple[Transform, str]] = []
    size = geom.size
    if geom.kind == "box":
        shapes.append((geom.pose, f'<box size="{output_list(2 * s for s in size[:3])}"/>'))
    elif geom.kind == "sphere":
        shapes.append((geom.pose, f'<sphere radius="{_n(size[0])}"/>'))
    elif geom.kind in ("cylinder", "capsule"):
        cylinder = f'<cylinder radius="{_n(size[0])}" length="{_n(2 * size[1])}"/>'
        shapes.append((geom.pose, cylinder))
        if geom.kind == "capsule":
            for sign in (1.0, -1.0):
                end = geom.pose.compose(Transform(position=(0.0, 0.0, sign * size[1])))
                shapes.append((end, f'<sphere radius="{_n(size[0])}"/>'))
    elif geom.kind == "ellipsoid":
        mesh = files.add_shape("ellipsoid", *_ellipsoid(size))
        files.use(mesh, geom.rgba if role == "visual" else None)
        key = colour_key(geom.rgba) if role == "visual" else ""
        shapes.append((geom.pose, f'<mesh filename="@MESH:{mesh}:{key}@"/>'))
    else:  # mesh
        assert geom.mesh is not None, "a geom of kind mesh has its mesh"
        files.use(geom.mesh, geom.rgba if role == "visual" else None)
        key = colour_key(geom.rgba) if role == "visual" else ""
        shapes.append((geom.pose, f'<mesh filename="@MESH:{geom.mesh}:{key}@"/>'))
    lines = []
    for pose, shape in shapes:
        lines.append(f"    <{role}>{_origin(pose)}<geometry>{shape}</geometry>{material}</{role}>")
    return lines


def _ellipsoid(size) -> tuple:
    """Vertices and triangles of an ellipsoid with semi-axes ``size``."""
    import numpy as np

    rings, segments = ELLIPSOID_SEGMENTS // 2, ELLIPSOID_SEGMENTS
    theta = np.linspace(0.0, math.pi, rings + 1)[1:-1]
    phi = np.linspace(0.0, 2 * math.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)
    vertices = np.vstack([[0.0, 0.0, 1.0], ring.reshape(-1, 3), [0.0, 0.0, -1.0]])
    vertices = vertices * np.asarray(size[:3], dtype=float)
    faces = []
    last = len(vertices) - 1
    for s in range(segments):
        faces.append((0, 1 + s, 1 + (s + 1) % segments))
        base = 1 + (rings - 2) * segments
        faces.append((last, base + (s + 1) % segments, base + s))
    for r in range(rings - 2):
        for s in range(segments):
            a, b = 1 + r * segments + s, 1 + r * segments + (s + 1) % segments
            c, d = a + segments, b + segments
            faces += [(a, c, b), (b, c, d)]
    return vertices, np.asarray(faces, dtype=int)


def _joint_lines(joint: _Joint) -> list[str]:
    lines = [
        f'  <joint name={xml_attribute(joint.name)} type="{joint.kind}">',
        f"    <parent link={xml_attribute(joint.parent)}/>",
        f"    <child link={xml_attribute(joint.child)}/>",
    ]
    origin = _origin(joint.origin)
    if origin:
        lines.append(f"    {origin}")
    if joint.axis is not None and joint.kind not in ("fixed", "floating"):
        lines.append(f'    <axis xyz="{output_list(joint.axis)}"/>')
    if joint.limit is not None:
        lower, upper, effort = joint.limit
        bounds = ""
        if lower is not None and upper is not None:
            bounds = f'lower="{_n(lower)}" upper="{_n(upper)}" '
        velocity = _n(joint.velocity) if joint.velocity is not None else "0"
        lines.append(f'    <limit {bounds}effort="{_n(effort)}" velocity="{velocity}"/>')
    if joint.damping or joint.friction:
        lines.append(
            f'    <dynamics damping="{_n(joint.damping)}" friction="{_n(joint.friction)}"/>'
        )
    if joint.mimic is not None:
        leader, multiplier, offset = joint.mimic
        lines.append(
            f'    <mimic joint={xml_attribute(leader)} multiplier="{_n(multiplier)}" '
            f'offset="{_n(offset)}"/>'
        )
    lines.append("  </joint>")
    return lines


def _origin(pose: Transform) -> str:
    if pose.is_identity:
        return ""
    urdf = pose.to_pose()
    # Rounding noise (1e-17 where MuJoCo computed a zero) says nothing; write it as 0.
    urdf = type(urdf)(vec3(0.0 if abs(v) < 1e-15 else v for v in urdf.xyz), urdf.rpy)
    return f'<origin xyz="{output_list(urdf.xyz)}" rpy="{output_list(urdf.rpy)}"/>'


def _near_identity(pose: Transform) -> bool:
    rotation_error = max(
        abs(pose.rotation[i][j] - (1.0 if i == j else 0.0)) for i in range(3) for j in range(3)
    )
    return max(abs(v) for v in pose.position) < 1e-9 and rotation_error < 1e-9


def _minus(a, b) -> tuple[float, float, float]:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _n(value: float) -> str:
    return output_list([value])
