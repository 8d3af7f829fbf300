"""Where cameras and lidars go, from the link frame they are attached to.

A ROS optical frame looks along +z with +y down in the image; a MuJoCo camera looks along -z
with +y up. The camera is the link frame turned half a turn about its x axis.

A lidar link has +z up and the first ray along +x turned by ``min_angle`` about +z (a ROS
LaserScan sweeps counterclockwise). MuJoCo rangefinders measure along their site's +z. The
rays are the sites of a ``<replicate>`` that turns each copy by ``angle_increment`` about the
y axis of a body whose y axis is the link's z axis and whose z axis is the first ray (written
out site by site before the model is compiled: ``mjcfbuild.inputs.rays``).
"""

from __future__ import annotations

import math

from mjcfbuild.urdf.transforms import Transform, quat_to_matrix

HALF_TURN_ABOUT_X = Transform(quat_to_matrix((0.0, 1.0, 0.0, 0.0)))
# x -> y, y -> z, z -> x: the body's z (first ray) is the link's x, its y the link's z.
RANGEFINDER_AXES = Transform(quat_to_matrix((0.5, 0.5, 0.5, 0.5)))


def camera_pose(link: Transform) -> Transform:
    """The MuJoCo camera frame for a ROS optical frame at ``link``."""
    return link.compose(HALF_TURN_ABOUT_X)


def lidar_body_pose(link: Transform, min_angle: float) -> Transform:
    """The frame of the body holding the lidar's replicated rangefinder sites."""
    turn = Transform(
        (
            (math.cos(min_angle), 0.0, math.sin(min_angle)),
            (0.0, 1.0, 0.0),
            (-math.sin(min_angle), 0.0, math.cos(min_angle)),
        )
    )
    return link.compose(RANGEFINDER_AXES).compose(turn)


def ray_count(min_angle: float, max_angle: float, increment: float) -> int:
    """How many rays from ``min_angle`` by ``increment``: mujoco_ros2_control's count (and the
    reference converter's), ``int((max - min) / increment) + 1``, which is the number of
    ranges its scan holds. It truncates in floating point: -0.3 to 0.3 by 0.025 is 24 rays,
    0.6 / 0.025 being 23.999999999999996 (see :func:`rays_short_of_max`)."""
    return int((max_angle - min_angle) / increment) + 1


def rays_short_of_max(min_angle: float, max_angle: float, increment: float) -> bool:
    """Whether :func:`ray_count`'s truncation leaves out a ray at ``max_angle`` that the
    angles mean to have (their span a whole number of increments but for rounding)."""
    steps = (max_angle - min_angle) / increment
    whole = math.floor(steps + 1e-9 * max(1.0, abs(steps)))
    return whole + 1 != ray_count(min_angle, max_angle, increment)


def ray_direction(link: Transform, min_angle: float, increment: float, index: int):
    """The direction (in the link's parent frame) of ray ``index``: expected by the tests."""
    angle = min_angle + index * increment
    local = (math.cos(angle), math.sin(angle), 0.0)
    r = link.rotation
    return tuple(sum(r[i][k] * local[k] for k in range(3)) for i in range(3))
