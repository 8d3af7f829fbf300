"""Whether a robot's base floats, decided from its kinematics and geometry, not its names.

For ``mjcfbuild init``: names lie (a humanoid whose joints are called ``leg_left_4_joint``, a
wheeled base whose casters are called ``*_hip_*``). At the zero pose, with every link placed by
forward kinematics and each link's shapes reduced to points (their origins, and the corners of
boxes, cylinders and spheres):

- a robot bolted down says so: its root is a ``world`` link joined by a fixed joint; one
  joined by a floating joint says it floats;
- a robot without moving joints floats: fixed, nothing in it could ever move; free, forces
  move it (hector's quadrotor, one link). A fixture meant to stay put (a sensor mount, a
  table) takes ``free_joint: false``;
- a wheeled base floats: two or more continuous joints with horizontal axes whose links sit in
  the lowest quarter of the robot (or in its lower half, below every other moving joint: a
  low-slung base);
- a legged robot floats: a link branches into two or more limbs that reach the floor (within
  10% of the robot's height of its lowest point) while the root itself stays well above it
  (more than 30% of the robot's height); but three or more such limbs hanging from a root at
  the top of the robot whose ends lie in a row (no support area between them) are a hand's
  fingers, not legs;
- a flying robot floats: two or more joints without stops, with vertical axes, at leaf links
  (rotors);
- anything else (an arm on its base plate, a hand) is fixed.
"""

from __future__ import annotations

from dataclasses import dataclass

from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.model import Joint, Robot, Shape
from mjcfbuild.urdf.transforms import Transform, apply

_FLOOR = 0.1  # of the height: how close to the lowest point a foot reaches
_RAISED = 0.3  # of the height: how far above the lowest point a walking root stays
_WHEEL_ZONE = 0.25  # of the height: where wheels sit
# Width over length of the ends of three or more limbs, below which they lie in a row: real
# quadrupeds' and hexapods' feet 0.5-0.9, hands' hanging fingertips 0.05-0.2.
_ROW = 0.25


@dataclass(frozen=True)
class BaseKind:
    """Whether the base floats and why."""

    floating: bool
    why: str


def classify_base(robot: Robot) -> BaseKind:
    """Decide whether ``robot``'s base floats (see the module's rules)."""
    kinds = {joint.kind for joint in robot.joints if joint.parent == robot.root}
    if "floating" in kinds:  # MuJoCo's import makes it a free joint: the build floats it
        return BaseKind(True, "its URDF joins it to the world with a floating joint")
    if robot.root == "world":
        return BaseKind(False, "its root is joined to the world link")
    if all(joint.kind == "fixed" for joint in robot.joints):
        return BaseKind(
            True,
            "it has no moving joints: fixed, nothing in it could move; free, forces move it "
            "(a drone); false for a fixture that stays put",
        )
    poses = link_poses(robot)
    points = {link.name: _points(link.shapes, poses[link.name]) for link in robot.links}
    heights = [p[2] for values in points.values() for p in values]
    if not heights:
        return BaseKind(False, "it has no geometry to stand on")
    low, high = min(heights), max(heights)
    size = max(high - low, 1e-6)
    wheels = _wheels(robot, poses, low, size)
    if len(wheels) >= 2:
        return BaseKind(True, f"its continuous joints {', '.join(wheels[:4])} are wheels")
    rotors = _rotors(robot, poses)
    if len(rotors) >= 2:
        return BaseKind(True, f"its continuous joints {', '.join(rotors[:4])} are rotors")
    body = _fixed_to(robot, robot.root)
    feet = _branches_reaching(robot, points, low + _FLOOR * size)
    root_low = min(p[2] for link in body for p in points[link])
    root_high = max(p[2] for link in body for p in points[link])
    hanging = root_high > high - _FLOOR * size  # nothing of the robot above its root
    if hanging and len(feet) >= 3 and _in_a_row(_feet(robot, points, feet)):
        return BaseKind(
            False,
            f"its {len(feet)} limbs that reach down ({', '.join(sorted(feet)[:4])}) end in a "
            "row, as a hand's fingers hang, not spread as legs stand",
        )
    if len(feet) >= 2 and root_low - low > _RAISED * size:
        return BaseKind(
            True,
            f"{len(feet)} limbs ({', '.join(sorted(feet)[:4])}) reach {root_low - low:.2f} m "
            "below its root to the floor",
        )
    return BaseKind(False, "its root sits at the bottom of the robot")


def _points(shapes: list[Shape], pose: Transform) -> list[tuple[float, float, float]]:
    """World points of a link's shapes: origins, and corners of primitives."""
    found = [pose.position]
    for shape in shapes:
        frame = pose.compose(Transform.from_pose(shape.origin))
        for offset in _corners(shape):
            moved = apply(frame.rotation, offset)
            found.append(
                (
                    frame.position[0] + moved[0],
                    frame.position[1] + moved[1],
                    frame.position[2] + moved[2],
                )
            )
    return found


def _corners(shape: Shape) -> list[tuple[float, float, float]]:
    geometry = shape.geometry
    size = geometry.size
    if geometry.kind == "box" and len(size) == 3:
        x, y, z = (s / 2 for s in size)
    elif geometry.kind in ("cylinder", "capsule") and len(size) == 2:
        x = y = size[0]
        z = size[1] / 2 + (size[0] if geometry.kind == "capsule" else 0.0)
    elif geometry.kind == "sphere" and size:
        x = y = z = size[0]
    else:
        return [(0.0, 0.0, 0.0)]
    return [(a, b, c) for a in (-x, x) for b in (-y, y) for c in (-z, z)]


def _wheels(robot: Robot, poses: dict[str, Transform], low: float, size: float) -> list[str]:
    """Continuous joints with about horizontal axes that sit low: in the lowest quarter of the
    robot, or (a low-slung base, whose wheels are a large share of its height) in its lower
    half with no other moving joint below them."""
    candidates = {}
    for joint in robot.joints:
        if joint.kind != "continuous":
            continue
        pose = poses[joint.child]
        axis = apply(pose.rotation, joint.axis)
        norm = sum(a * a for a in axis) ** 0.5 or 1.0
        if abs(axis[2] / norm) < 0.3:
            candidates[joint.name] = pose.position[2] - low
    others = [
        poses[joint.child].position[2] - low
        for joint in robot.joints
        if joint.kind != "fixed" and joint.name not in candidates
    ]
    lowest_other = min(others, default=float("inf"))
    return [
        name
        for name, height in candidates.items()
        if height <= _WHEEL_ZONE * size or (height <= 0.5 * size and height < lowest_other)
    ]


def _rotors(robot: Robot, poses: dict[str, Transform]) -> list[str]:
    """Joints that turn without stops, with vertical axes, at leaf links: propellers."""
    parents = {joint.parent for joint in robot.joints}
    rotors = []
    for joint in robot.joints:
        if not _unbounded(joint) or joint.child in parents:
            continue
        axis = apply(poses[joint.child].rotation, joint.axis)
        norm = sum(a * a for a in axis) ** 0.5 or 1.0
        if abs(axis[2] / norm) > 0.9:
            rotors.append(joint.name)
    return rotors


def _unbounded(joint: Joint) -> bool:
    """Continuous, or revolute without a range or with a placeholder one (+-1e16)."""
    from mjcfbuild.urdf.limits import joint_range

    if joint.kind == "continuous":
        return True
    bounds = joint_range(joint)
    return joint.kind == "revolute" and (bounds is None or max(map(abs, bounds)) > 1e4)


def _fixed_to(robot: Robot, root: str) -> set[str]:
    """``root`` and the links fixed to it (one rigid body once fixed joints are merged)."""
    body = {root}
    changed = True
    while changed:
        changed = False
        for joint in robot.joints:
            if joint.kind == "fixed" and joint.parent in body and joint.child not in body:
                body.add(joint.child)
                changed = True
    return body


def _children(robot: Robot) -> dict[str, list[str]]:
    """Each link's child links."""
    children: dict[str, list[str]] = {}
    for joint in robot.joints:
        children.setdefault(joint.parent, []).append(joint.child)
    return children


def _branches_reaching(robot: Robot, points: dict, floor: float) -> set[str]:
    """The most links one link branches into whose subtrees reach down to ``floor``: a
    pelvis's two legs, a trunk's four, even where the legs hang from a waist below the root."""
    children = _children(robot)
    reaches: dict[str, bool] = {}
    for link in _bottom_up(children, robot.root):
        own = any(p[2] <= floor for p in points.get(link, []))
        reaches[link] = own or any(reaches[child] for child in children.get(link, []))

    best: set[str] = set()
    for link in [robot.root, *(joint.child for joint in robot.joints)]:
        legs = {child for child in children.get(link, []) if reaches.get(child)}
        if len(legs) > len(best):
            best = legs
    return best


def _feet(robot: Robot, points: dict, limbs: set[str]) -> list[tuple[float, float, float]]:
    """The lowest point of each of ``limbs``' subtrees."""
    children = _children(robot)
    feet = []
    for limb in sorted(limbs):
        lowest: dict[str, tuple[float, float, float] | None] = {}
        for link in _bottom_up(children, limb):
            below = [lowest[child] for child in children.get(link, [])]
            candidates = [*points.get(link, []), *(p for p in below if p is not None)]
            lowest[link] = min(candidates, key=lambda p: p[2]) if candidates else None
        foot = lowest[limb]
        assert foot is not None, "a limb is chosen for a point of its subtree on the floor"
        feet.append(foot)
    return feet


def _bottom_up(children: dict[str, list[str]], top: str) -> list[str]:
    """``top`` and the links below it, every child before its parent (no recursion: chains
    are thousands of links deep)."""
    order = []
    pending = [top]
    while pending:
        link = pending.pop()
        order.append(link)
        pending.extend(children.get(link, []))
    return order[::-1]


def _in_a_row(feet: list[tuple[float, float, float]]) -> bool:
    """Whether points lie in a row seen from above: their narrowest extent (over directions 5
    degrees apart) is under :data:`_ROW` times their widest."""
    import math

    extents = []
    for step in range(36):
        angle = math.pi * step / 36
        along = [p[0] * math.cos(angle) + p[1] * math.sin(angle) for p in feet]
        extents.append(max(along) - min(along))
    return min(extents) < _ROW * max(extents)
