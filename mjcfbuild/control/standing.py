"""What a floating robot standing at home needs from its servos, and whether it can stand.

A robot held by position servos at home is an inverted pendulum over its feet: tilting the
part of the robot that a weight-bearing joint carries by a small angle makes gravity push it
further, with a stiffness of about m g h (the carried mass, gravity, and the height of its
centre of mass over the joint). A servo softer than that lets the robot tip slowly and fall
after seconds (a 67 kg humanoid with its centre of mass 0.94 m up fell with ankle kp 318 and
stood with 2000). Gains sized from a joint's own inertia (the foot's, for an ankle) are far
softer, so every joint between the floating base and a foot on the floor gets at least
:data:`MARGIN` times its share of that gravity stiffness (the feet on the floor share it).

Damping is sized from what the joint moves while standing (its own inertia plus the carried
mass at its lever), not from the foot alone, so the stiff servo is critically damped where it
matters and, treated implicitly, stays stable when the foot is in the air.

A robot stands on its own only where its feet span an area: point or line contacts (two
spheres, two wheels on one axle, a single foot) need a balance controller, and a robot whose
geometry does not reach the floor at home (a drone in the air) has nothing to stand on.
"""

from __future__ import annotations

from dataclasses import dataclass

# Weight-bearing servos get this many times their share of the gravity stiffness m g h:
# measured on humanoids and quadrupeds (docs/simulation.md), 3 keeps the base within a few
# degrees for 5 s; below about 1.5 they tip over.
MARGIN = 3.0
CONTACT = 2e-3  # m: collision geometry this close to the floor at home touches it
AREA = 1e-4  # m^2: feet spanning less than this (1 cm^2) give no support polygon


@dataclass(frozen=True)
class Stance:
    """How a floating robot meets the floor at home."""

    feet: dict[int, list[float]]  # body -> its lowest point on the floor
    area: float  # of the support polygon (m^2)
    com_inside: bool  # whether the centre of mass is over the support polygon
    margin: float  # distance from the centre of mass to the polygon's edge (m; < 0 outside)
    colliding: bool = True  # whether the robot has collision geometry at all

    @property
    def can_stand(self) -> bool:
        """Whether the feet span an area the centre of mass lies over."""
        return self.area >= AREA and self.com_inside

    def why_not(self) -> str:
        """Why the robot cannot stand passively, for the report ('' if it can)."""
        if not self.feet and not self.colliding:
            return "it has no collision geometry to stand on (the URDF has no <collision>)"
        if not self.feet:
            return "none of its collision geometry touches the floor at home"
        if self.area < AREA:
            what = "a point" if len(self.feet) == 1 else "a line"
            return (
                f"its feet touch the floor at {what} ({len(self.feet)} contact "
                f"bod{'y' if len(self.feet) == 1 else 'ies'}): it balances only under a "
                "controller"
            )
        if not self.com_inside:
            return (
                f"its centre of mass is {-self.margin * 1000:.0f} mm outside the area its "
                "feet span at home"
            )
        return ""


def stance(model, data, rolling: frozenset[int] = frozenset()) -> Stance:
    """The feet and support polygon of ``data``'s pose (kinematics and centre of mass
    computed, the robot standing on z = 0). ``rolling`` bodies (wheels) touch the floor at
    their lowest point only: a tyre's flat band is no foot."""
    import numpy as np

    from mjcfbuild.control.floor import geom_lowest_points, geom_support_points

    feet: dict[int, list[float]] = {}
    points = []
    for geom, point in geom_lowest_points(model, data).items():
        if point[2] > CONTACT:
            continue
        body = int(model.geom_bodyid[geom])
        feet.setdefault(body, [float(v) for v in point])
        if body in rolling:
            points.append(point[:2])
        else:
            points += [p[:2] for p in geom_support_points(model, data, geom, CONTACT)]
    com = np.asarray(data.subtree_com[0][:2])
    if len(points) < 3:
        robot = model.geom_bodyid != 0
        colliding = bool(
            np.any(robot & ((model.geom_contype != 0) | (model.geom_conaffinity != 0)))
        )
        return Stance(feet, 0.0, False, -1.0, colliding)
    hull = _hull(np.asarray(points))
    area = _area(hull)
    margin = _inside_margin(hull, com) if area >= AREA else -1.0
    return Stance(feet, area, margin >= 0, margin)


def pendulum_loads(model, data, feet: dict[int, list[float]]):
    """Per degree of freedom, the gravity stiffness (N m/rad) and the inertia (kg m^2) that a
    hinge between the floating base and a foot on the floor carries while standing, each
    joint's share of the feet (zero for other joints)."""
    import mujoco
    import numpy as np

    from mjcfbuild.control.efforts import subtree

    stiffness = np.zeros(model.nv)
    carried = np.zeros(model.nv)
    if not feet:
        return stiffness, carried
    total = float(model.body_subtreemass[0])
    gravity = np.asarray(model.opt.gravity, dtype=float)
    centre = np.asarray(data.subtree_com[0])
    for joint in range(model.njnt):
        if model.jnt_type[joint] != mujoco.mjtJoint.mjJNT_HINGE:
            continue
        body = int(model.jnt_bodyid[joint])
        below = subtree(model, body)
        if not any(foot in below for foot in feet):
            continue
        mass = total - float(model.body_subtreemass[body])
        if mass <= 0:
            continue
        com = (total * centre - model.body_subtreemass[body] * data.subtree_com[body]) / mass
        axis = np.asarray(data.xaxis[joint])
        lever = com - data.xanchor[joint]
        # d(torque)/d(angle) of gravity on the carried part rotated about the axis: positive
        # where gravity pushes a tilt further (an inverted pendulum).
        rate = float(axis @ np.cross(np.cross(axis, lever), mass * gravity))
        share = len(feet)
        dof = int(model.jnt_dofadr[joint])
        stiffness[dof] = max(rate, 0.0) / share
        perpendicular = lever - (lever @ axis) * axis
        carried[dof] = mass * float(perpendicular @ perpendicular) / share
    return stiffness, carried


def rolling_bodies(model, data) -> frozenset[int]:
    """The bodies of unlimited hinge joints that are wheels on the floor (control.wheels)."""
    import mujoco

    from mjcfbuild.control.wheels import wheel_joints

    hinges = [
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, joint) or ""
        for joint in range(model.njnt)
        if model.jnt_type[joint] == mujoco.mjtJoint.mjJNT_HINGE and not model.jnt_limited[joint]
    ]
    wheels = wheel_joints(model, data, [name for name in hinges if name])
    return frozenset(
        int(model.jnt_bodyid[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)])
        for name in wheels
    )


def mirror_pairs(model, data, joints: list[str], tolerance: float = 0.01) -> list[tuple[str, str]]:
    """Pairs of ``joints`` that mirror each other across the base's sagittal (x-z) plane:
    anchors mirrored within ``tolerance`` (m) and axes mirrored, in the base's frame."""
    import mujoco
    import numpy as np

    root = _root_body(model)
    origin = data.xpos[root]
    frame = data.xmat[root].reshape(3, 3)
    placed = {}
    for name in joints:
        joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if joint < 0 or model.jnt_type[joint] != mujoco.mjtJoint.mjJNT_HINGE:
            continue
        anchor = frame.T @ (data.xanchor[joint] - origin)
        axis = frame.T @ data.xaxis[joint]
        placed[name] = (anchor, axis)
    pairs = []
    taken: set[str] = set()
    flip = np.array([1.0, -1.0, 1.0])
    for name, (anchor, axis) in placed.items():
        if name in taken or abs(anchor[1]) <= tolerance:
            continue
        mirrored_axis = -axis * flip  # an axial vector mirrors with a sign change
        for other, (other_anchor, other_axis) in placed.items():
            if other == name or other in taken:
                continue
            if np.linalg.norm(other_anchor - anchor * flip) > tolerance:
                continue
            if abs(float(other_axis @ mirrored_axis)) < 0.99:
                continue
            pairs.append((name, other))
            taken |= {name, other}
            break
    return pairs


def _root_body(model) -> int:
    import mujoco

    for joint in range(model.njnt):
        if model.jnt_type[joint] == mujoco.mjtJoint.mjJNT_FREE:
            return int(model.jnt_bodyid[joint])
    return 1 if model.nbody > 1 else 0


def _hull(points):
    """The convex hull of 2-D ``points``, counter-clockwise (Andrew's monotone chain)."""
    import numpy as np

    unique = sorted({(round(float(x), 9), round(float(y), 9)) for x, y in points})
    if len(unique) < 3:
        return np.asarray(unique)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list = []
    for point in unique:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], point) <= 0:
            lower.pop()
        lower.append(point)
    upper: list = []
    for point in reversed(unique):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], point) <= 0:
            upper.pop()
        upper.append(point)
    return np.asarray(lower[:-1] + upper[:-1])


def _area(hull) -> float:
    if len(hull) < 3:
        return 0.0
    import numpy as np

    x, y = hull[:, 0], hull[:, 1]
    return 0.5 * abs(float((x * np.roll(y, -1)).sum() - (y * np.roll(x, -1)).sum()))


def _inside_margin(hull, point) -> float:
    """The distance from ``point`` to the nearest edge of the counter-clockwise ``hull``:
    positive inside, negative outside."""
    import numpy as np

    margin = float("inf")
    for index in range(len(hull)):
        start, end = hull[index], hull[(index + 1) % len(hull)]
        edge = end - start
        length = float(np.linalg.norm(edge))
        if length == 0:
            continue
        signed = float(edge[0] * (point[1] - start[1]) - edge[1] * (point[0] - start[0])) / length
        margin = min(margin, signed)
    return margin
