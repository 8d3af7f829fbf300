"""The part of a robot that decides its contacts, as the collision matrix task's input."""

from __future__ import annotations

from dataclasses import replace

from mjcfbuild.collision.policy import CollisionChoice
from mjcfbuild.urdf.model import Inertial, Joint, Limit, Pose, Robot

# Every link weighs the same in the collision model: masses do not decide contacts, and an
# inertia edit must not rerun the matrix.
_UNIT_INERTIAL = Inertial(Pose(), 1.0, (0.01, 0.0, 0.0, 0.01, 0.0, 0.01))


def collision_robot(robot: Robot, choices: list[CollisionChoice]) -> Robot:
    """``robot`` with only the shapes collision geometry is made from and unit inertias.

    Joints keep their kinematics (the matrix only poses the robot) but not their dynamics,
    effort or velocity. Line numbers stay, so errors in collision geometry point at their line
    (an edit that moves lines reruns the matrix; one that changes a visual mesh, an inertia or
    a joint's damping does not)."""
    used = {(c.link, c.role, c.index) for c in choices}
    links = []
    for link in robot.links:

        def kept(shapes, link_name=link.name):
            return [
                replace(shape, name=None, material=None)
                for shape in shapes
                if (link_name, shape.role, shape.index) in used
            ]

        links.append(
            replace(
                link,
                inertial=_UNIT_INERTIAL,
                visuals=kept(link.visuals),
                collisions=kept(link.collisions),
            )
        )
    return replace(robot, links=links, joints=[_kinematic(j) for j in robot.joints], warnings=[])


def _kinematic(joint: Joint) -> Joint:
    """``joint`` without what does not move it: dynamics, effort and velocity limits."""
    limit = joint.limit and Limit(joint.limit.lower, joint.limit.upper)
    return replace(joint, limit=limit, damping=0.0, friction=0.0)
