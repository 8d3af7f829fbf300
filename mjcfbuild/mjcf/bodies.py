"""From URDF links to MuJoCo bodies: which links fuse, where everything sits, combined masses.

With fusing on, a link attached by a fixed joint becomes part of its parent's body: its shapes
and inertia move into the parent's frame and its name survives as a site. Everything here is
computed in double precision from the URDF, so the assembled model's numbers are the URDF's,
not a re-parse of rounded text.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mjcfbuild.urdf.model import WORLD, Joint, Robot, Shape
from mjcfbuild.urdf.transforms import Matrix, Transform, matmul, matrix3, transpose, vec3


@dataclass
class MassProperties:
    """Mass, centre of mass and inertia tensor about it, all in the body frame."""

    mass: float
    com: tuple[float, float, float]
    inertia: Matrix
    links: list[str] = field(default_factory=list)


@dataclass
class PlacedShape:
    """A URDF visual or collision, placed in the frame of the body it ends up in."""

    link: str
    shape: Shape
    pose: Transform


@dataclass
class LinkFrame:
    """Where a URDF link's frame is, in the frame of the body it ends up in."""

    link: str
    pose: Transform
    fused: bool


@dataclass
class Body:
    """One MuJoCo body: a URDF link and the fixed-joint links fused into it."""

    name: str
    parent: str | None
    joint: Joint | None  # the URDF joint to the parent body (fixed when not fusing)
    pose: Transform
    mass: MassProperties | None
    shapes: list[PlacedShape]
    links: list[LinkFrame]
    floating: bool = False  # gets a free joint

    @property
    def moves(self) -> bool:
        """Whether the body has its own degrees of freedom."""
        return self.floating or (self.joint is not None and self.joint.moves)


def link_places(bodies: list[Body]) -> dict[str, tuple[str | None, Transform]]:
    """Each URDF link's place among ``bodies``: the body its frame is in (None for the world
    body) and the frame's pose there."""
    return {
        frame.link: (None if body.parent is None and body.name == WORLD else body.name, frame.pose)
        for body in bodies
        for frame in body.links
    }


def build_bodies(robot: Robot, fuse_static: bool, free_joint: bool = False) -> list[Body]:
    """The bodies of the model, parents before children, in URDF order; with ``free_joint``
    (robot.yaml's), the one that gets a free joint is marked ``floating``: the root.

    A root link called ``world`` stands for MuJoCo's world body; links fixed to it become
    static parts of the world when fusing. ``free_joint`` on such a URDF floats what the world
    holds instead, as one rigid whole, as the URDF joins it: the heaviest link fixed to the
    world becomes the floating body, and everything else the world holds (a camera mount, a
    second fixed link, a joint whose parent is ``world``) hangs from it where the URDF puts
    it, so that no part floats away on its own.
    """
    children = robot.child_joints()
    links = {link.name: link for link in robot.links}
    carrier = _carrier(robot, children) if free_joint and robot.root == WORLD else None
    bodies: list[Body] = []
    # Depth first with an explicit stack, not recursion: chains (snakes, ropes) are thousands
    # of links deep. An entry is a link to place in ``body`` at ``in_body``; a None body
    # starts a new body for the link, hanging from ``parent`` by ``joint`` at ``in_body``.
    pending: list[tuple[str, Body | None, str | None, Joint | None, Transform]] = [
        (robot.root, None, None, None, Transform())
    ]
    ground = ground_link(robot)
    while pending:
        link_name, body, parent, joint, in_body = pending.pop()
        if body is None:
            # The ground link is MuJoCo's world body, whatever its name (a root holding the
            # robot by a floating joint keeps its name as a site there).
            name = WORLD if parent is None and link_name == ground else link_name
            floating = free_joint and parent is None and name != WORLD
            body = Body(name, parent, joint, in_body, None, [], [], floating)
            bodies.append(body)
            in_body = Transform()
        link = links[link_name]
        body.links.append(LinkFrame(link_name, in_body, fused=link_name != body.name))
        for shape in link.shapes:
            body.shapes.append(
                PlacedShape(link_name, shape, in_body.compose(Transform.from_pose(shape.origin)))
            )
        below: list[tuple[str, Body | None, str | None, Joint | None, Transform]] = []
        if carrier is not None and link_name == WORLD and body.parent is None:
            # The carrier's body comes first, so that the world's other children can join it.
            carrier_pose = Transform.from_pose(carrier.origin)
            carried = Body(carrier.child, WORLD, carrier, carrier_pose, None, [], [], True)
            bodies.append(carried)
            below.append((carrier.child, carried, None, None, Transform()))
            body, in_body = carried, carrier_pose.inverse()
        for child in children[link_name]:
            if child is carrier:
                continue
            joint_pose = in_body.compose(Transform.from_pose(child.origin))
            if fuse_static and not child.moves:
                below.append((child.child, body, None, None, joint_pose))
            else:
                below.append((child.child, None, body.name, child, joint_pose))
        pending.extend(reversed(below))  # the first child is placed next, as URDF orders them
    for body in bodies:
        body.mass = combine_masses(robot, body)
    return bodies


def _carrier(robot: Robot, children: dict[str, list[Joint]]) -> Joint | None:
    """The fixed joint from ``world`` to the link that floats for the whole robot: the one
    whose subtree is heaviest (the first of equals). None when the world holds no link fixed,
    or when the URDF floats its robot by a ``floating`` joint of its own: what it bolts to the
    world beside that stays bolted (and a free joint can only join a body to the world)."""
    if _floating_from(robot, fixed_to_root(robot)):
        return None
    fixed = [joint for joint in children[WORLD] if not joint.moves]
    if not fixed:
        return None

    def subtree_mass(link_name: str) -> float:
        total, stack = 0.0, [link_name]
        while stack:
            name = stack.pop()
            inertial = robot.link(name).inertial
            total += inertial.mass if inertial is not None else 0.0
            stack.extend(joint.child for joint in children[name])
        return total

    heaviest = max(subtree_mass(joint.child) for joint in fixed)
    return next(joint for joint in fixed if subtree_mass(joint.child) == heaviest)


def combine_masses(robot: Robot, body: Body) -> MassProperties | None:
    """The combined mass properties of every link in ``body``, or None if none has mass data."""
    parts = []
    for frame in body.links:
        inertial = robot.link(frame.link).inertial
        if inertial is None:
            continue
        to_body = frame.pose.compose(Transform.from_pose(inertial.origin))
        ixx, ixy, ixz, iyy, iyz, izz = inertial.inertia
        local = ((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz))
        rotated = matmul(matmul(to_body.rotation, local), transpose(to_body.rotation))
        parts.append((frame.link, inertial.mass, to_body.position, rotated))
    if not parts:
        return None
    total = sum(mass for _, mass, _, _ in parts)
    if total > 0:
        com = vec3(sum(mass * pos[i] for _, mass, pos, _ in parts) / total for i in range(3))
    else:
        com = parts[0][2]
    inertia = [[0.0] * 3 for _ in range(3)]
    for _, mass, pos, rotated in parts:
        d = tuple(pos[i] - com[i] for i in range(3))
        d2 = sum(v * v for v in d)
        for i in range(3):
            for j in range(3):
                inertia[i][j] += rotated[i][j] + mass * ((d2 if i == j else 0.0) - d[i] * d[j])
    return MassProperties(
        mass=total,
        com=com,
        inertia=matrix3(inertia),
        links=[name for name, _, _, _ in parts],
    )


def fixed_to_root(robot: Robot) -> set[str]:
    """The root and every link joined to it by fixed joints alone: with fusing on, the root's
    body (the world's, for a ground root)."""
    children = robot.child_joints()
    found, pending = {robot.root}, [robot.root]
    while pending:
        for joint in children[pending.pop()]:
            if not joint.moves:
                found.add(joint.child)
                pending.append(joint.child)
    return found


def _floating_from(robot: Robot, links: set[str]) -> list[Joint]:
    return [joint for joint in robot.joints if joint.kind == "floating" and joint.parent in links]


def ground_link(robot: Robot) -> str | None:
    """The URDF link that stands for MuJoCo's world body: a root called ``world``, or a root
    that holds the robot by a ``floating`` joint (on it, or on a link fixed to it), which
    MuJoCo allows only from the world: its own import fuses such a root into the world, as
    the placeholder root of HyQ's generated URDF."""
    root = robot.root
    if root == WORLD or _floating_from(robot, fixed_to_root(robot)):
        return root
    return None


def refuse_nested_floating(robot: Robot) -> None:
    """A ``floating`` joint below a moving joint: MuJoCo has free joints only on bodies of the
    world, so no model has it (urdfdom reads it; MuJoCo's import refuses it). One below links
    fixed to the root hangs from the world once they are fused (``options.fuse_static``)."""
    from mjcfbuild.errors import ModelError

    grounded = fixed_to_root(robot)
    for joint in robot.joints:
        if joint.kind == "floating" and joint.parent not in grounded:
            raise ModelError(
                f"joint '{joint.name}' is floating below link '{joint.parent}', which a moving "
                "joint holds: MuJoCo allows a floating joint only from the root (or links "
                "fixed to it)",
                file=robot.source,
                line=joint.line,
                hint="make it fixed or another kind; options.free_joint floats the whole "
                "robot from its root",
            )


def ground_notes(robot: Robot) -> list[str]:
    """What a root that stands for the world because it holds a floating joint leaves fixed
    in the world: its mass and geometry, and what its moving joints carry (MuJoCo's import
    does the same, silently)."""
    root = robot.root
    if root == WORLD or ground_link(robot) != root:
        return []
    link = robot.link(root)
    kept = []
    if link.inertial is not None and link.inertial.mass > 0:
        kept.append(f"its {link.inertial.mass:g} kg")
    if link.shapes:
        kept.append("its geometry")
    grounded = fixed_to_root(robot)
    moving = [
        j.name for j in robot.joints if j.parent in grounded and j.moves and j.kind != "floating"
    ]
    if moving:
        kept.append(f"joint{'s' if len(moving) > 1 else ''} {', '.join(moving[:3])}")
    if not kept:
        return []
    floating = _floating_from(robot, grounded)[0]
    where = f"{robot.source}:{floating.line}" if floating.line else robot.source
    return [
        f"{where}: link '{root}' holds the robot by the floating joint '{floating.name}', so "
        f"it stands for the world, as MuJoCo's import takes it: {', '.join(kept)} "
        f"{'stays' if kept == ['its geometry'] else 'stay'} fixed there (the floor and the "
        "check take it for the ground, not the robot); root the floating joint at a link of its "
        f"own if {'it belongs' if kept == ['its geometry'] else 'they belong'} to the robot"
    ]


def floating_base(robot: Robot, free_joint: bool) -> bool:
    """Whether the model's base floats: robot.yaml's ``options.free_joint`` asks for it, or the
    URDF itself joins its robot to the ground link (``world``, or a root standing for it) with
    a floating joint (MuJoCo's import makes that a free joint: the robot then stands on the
    floor as any floating base does)."""
    return free_joint or (
        ground_link(robot) is not None and bool(_floating_from(robot, fixed_to_root(robot)))
    )
