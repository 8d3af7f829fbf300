"""Telling a wheel from a revolving joint by what the compiled model shows.

URDFs declare wheels ``continuous``, but also arm joints that turn without stops and, in some
descriptions, every joint of a leg. A position servo holds those against gravity; a velocity
servo on them lets the limb sag (an arm's continuous shoulder drooped 0.51 rad in 1 s). So a
continuous joint is taken for a wheel only when its body is round about the joint's axis and
rolls on the floor at home:

- the axle is close to horizontal (within about 17 degrees);
- the body's geometry (collision geometry; visual meshes do not reach the compiles this runs
  on) has its outermost points, at the largest distance from the axis, all round the axis:
  every 30 degree sector holds a point within :data:`ROUND` of that radius;
- its lowest point lies within :data:`ON_FLOOR` of the robot's lowest collision point at
  home, and the axle is one radius above it.
"""

from __future__ import annotations

import math

ROUND = 0.1  # the rim's radius may vary by this fraction round the axis
ON_FLOOR = 0.02  # m: a wheel's lowest point is this close to the robot's lowest point
SECTORS = 12  # the rim must show in every one of these sectors round the axis
HORIZONTAL = 0.3  # |axis . z| below this: the axle is about horizontal


def wheel_joints(model, data, candidates: list[str]) -> set[str]:
    """The joints of ``candidates`` whose bodies are wheels on the floor in ``data``'s pose
    (kinematics computed)."""
    import mujoco

    from mjcfbuild.control.floor import body_points, lowest_collision_point

    lowest = lowest_collision_point(model, data)
    if lowest is None:
        return set()
    wheels = set()
    for name in candidates:
        joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if joint < 0 or model.jnt_type[joint] != mujoco.mjtJoint.mjJNT_HINGE:
            continue
        points = body_points(model, data, int(model.jnt_bodyid[joint]))
        if len(points) and _rolls(points, data.xanchor[joint], data.xaxis[joint], lowest.height):
            wheels.add(name)
    return wheels


def _rolls(points, anchor, axis, floor: float) -> bool:
    """Whether ``points`` are round about the axis through ``anchor`` and touch ``floor``."""
    import numpy as np

    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    if abs(axis[2]) > HORIZONTAL:
        return False
    relative = points - anchor
    radial = relative - np.outer(relative @ axis, axis)
    distance = np.linalg.norm(radial, axis=1)
    radius = float(distance.max())
    if radius <= 0:
        return False
    rim = radial[distance >= (1 - ROUND) * radius]
    first = np.cross(axis, [0.0, 0.0, 1.0])
    first /= np.linalg.norm(first)
    second = np.cross(axis, first)
    angles = np.arctan2(rim @ second, rim @ first)
    sectors = set(((angles + math.pi) / (2 * math.pi) * SECTORS).astype(int) % SECTORS)
    if len(sectors) < SECTORS:
        return False
    bottom = float(points[:, 2].min())
    axle_height = float(anchor[2]) - bottom
    return bottom - floor <= ON_FLOOR and abs(axle_height - radius) <= ROUND * radius + 0.005
