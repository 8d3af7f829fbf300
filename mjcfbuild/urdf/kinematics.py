"""Forward kinematics of a URDF, computed from the URDF alone.

This is the reference a built model is checked against, so it shares no code with MuJoCo's
URDF import: only the URDF's own joint origins and axes, in double precision.
"""

from __future__ import annotations

import math

from mjcfbuild.urdf.model import Robot
from mjcfbuild.urdf.transforms import Transform, axis_angle_matrix, vec3


def link_poses(robot: Robot, joint_values: dict[str, float] | None = None) -> dict[str, Transform]:
    """Every link's pose in the root link's frame.

    ``joint_values`` gives revolute and continuous angles (radians) and prismatic displacements
    (metres) by joint name; joints not given are at zero.
    """
    values = joint_values or {}
    poses = {robot.root: Transform()}
    children = robot.child_joints()
    pending = [robot.root]
    while pending:
        parent = pending.pop()
        for joint in children[parent]:
            pose = poses[parent].compose(Transform.from_pose(joint.origin))
            q = values.get(joint.name, 0.0)
            if joint.kind in ("revolute", "continuous"):
                pose = pose.compose(Transform(axis_angle_matrix(joint.axis, q)))
            elif joint.kind == "prismatic":
                norm = math.sqrt(sum(a * a for a in joint.axis))
                pose = pose.compose(Transform(position=vec3(a / norm * q for a in joint.axis)))
            poses[joint.child] = pose
            pending.append(joint.child)
    return poses
