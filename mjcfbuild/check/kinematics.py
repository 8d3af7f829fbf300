"""Forward kinematics of the built model against the URDF's, at random joint configurations.

The reference poses come from an independent reader of the URDF text
(:mod:`mjcfbuild.check.reference`, yourdfpy), or, where it cannot read the URDF, from
:func:`mjcfbuild.urdf.kinematics.link_poses` on mjcfbuild's own parse. The model's poses come
from MuJoCo's ``mj_kinematics``. Every URDF link must be a body or a site of its name in the
model, and sit where the URDF puts it.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

from mjcfbuild.check.reference import ReferenceKinematics
from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.limits import joint_range
from mjcfbuild.urdf.model import Robot
from mjcfbuild.urdf.transforms import matrix3, rotation_angle_between

MOVING = ("revolute", "continuous", "prismatic")


@dataclass
class LinkError:
    """The largest disagreement found for one link."""

    link: str
    position: float
    rotation: float
    configuration: int


@dataclass
class KinematicsResult:
    """How far the model's link poses are from the URDF's."""

    configurations: int
    max_position: float = 0.0
    max_rotation: float = 0.0
    worst: LinkError | None = None
    missing_links: list[str] = field(default_factory=list)
    missing_joints: list[str] = field(default_factory=list)
    per_link: dict[str, LinkError] = field(default_factory=dict)
    order: list[str] = field(default_factory=list)

    def first_wrong(self, position_tolerance: float, rotation_tolerance: float) -> LinkError | None:
        """The wrong link nearest the root: where an error starts (its descendants follow)."""
        for link in self.order:
            error = self.per_link.get(link)
            if error and (
                error.position > position_tolerance or error.rotation > rotation_tolerance
            ):
                return error
        return None

    def wrong_count(self, position_tolerance: float, rotation_tolerance: float) -> int:
        """How many links are off."""
        return sum(
            1
            for e in self.per_link.values()
            if e.position > position_tolerance or e.rotation > rotation_tolerance
        )

    def passes(self, position_tolerance: float = 1e-6, rotation_tolerance: float = 1e-6) -> bool:
        """Whether every link is present and within both tolerances."""
        return (
            not self.missing_links
            and not self.missing_joints
            and self.max_position <= position_tolerance
            and self.max_rotation <= rotation_tolerance
        )


def random_configurations(robot: Robot, count: int, seed: int = 0) -> list[dict[str, float]]:
    """``count`` joint configurations within the URDF limits; mimic joints follow their leader.

    The first configuration is all zeros.
    """
    rng = random.Random(seed)
    joints = {joint.name: joint for joint in robot.joints}
    result = []
    for index in range(count):
        values: dict[str, float] = {}
        for joint in robot.joints:
            if joint.kind not in MOVING or joint.mimic is not None:
                continue
            if index == 0:
                values[joint.name] = 0.0
                continue
            lower, upper = _limits(joint)
            values[joint.name] = rng.uniform(lower, upper)
        for joint in robot.joints:
            if joint.mimic is not None and joint.kind in MOVING:
                leader = values.get(joint.mimic.joint, 0.0)
                if joints[joint.mimic.joint].mimic is not None:
                    leader = 0.0  # chains of mimics are rare; keep them at rest
                values[joint.name] = joint.mimic.multiplier * leader + joint.mimic.offset
        result.append(values)
    return result


def _limits(joint) -> tuple[float, float]:
    bounds = joint_range(joint)
    if bounds is None:
        return (-math.pi, math.pi) if joint.kind != "prismatic" else (-0.5, 0.5)
    if bounds[1] <= bounds[0]:
        return bounds[0], bounds[0]
    return bounds


def compare_kinematics(
    robot: Robot,
    model,
    count: int = 20,
    seed: int = 0,
    reference: ReferenceKinematics | None = None,
) -> KinematicsResult:
    """Compare every URDF link's pose in ``model`` (an MjModel) with the URDF's.

    The URDF's poses come from ``reference`` (an independent reader of the URDF text) when
    given, else from mjcfbuild's own parse of it (``robot``, which also names the links).
    """
    import mujoco
    import numpy as np

    result = KinematicsResult(configurations=count)
    addresses = {}
    for joint in robot.joints:
        if joint.kind not in MOVING:
            continue
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint.name)
        if index < 0:
            result.missing_joints.append(joint.name)
        else:
            addresses[joint.name] = model.jnt_qposadr[index]
    frames = {}
    for link in robot.links:
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, link.name)
        site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, link.name)
        if body >= 0:
            frames[link.name] = ("body", body)
        elif site >= 0:
            frames[link.name] = ("site", site)
        elif link.name != "world":
            result.missing_links.append(link.name)
    result.order = _root_first(robot)
    data = mujoco.MjData(model)
    for number, values in enumerate(random_configurations(robot, count, seed)):
        expected = reference.poses(values) if reference else link_poses(robot, values)
        qpos = model.qpos0.copy()
        for jnt in range(model.njnt):
            if model.jnt_type[jnt] == mujoco.mjtJoint.mjJNT_FREE:
                # A free body sits where the URDF places its link at rest: the root at the
                # origin, the child of a floating joint from `world` at that joint's origin.
                address = model.jnt_qposadr[jnt]
                qpos[address : address + 7] = _resting(model, jnt, expected)
        for name, address in addresses.items():
            qpos[address] = values.get(name, 0.0)
        data.qpos[:] = qpos
        mujoco.mj_kinematics(model, data)
        for link_name, (kind, index) in frames.items():
            if link_name not in expected:
                continue
            if kind == "body":
                position, matrix = data.xpos[index], data.xmat[index]
            else:
                position, matrix = data.site_xpos[index], data.site_xmat[index]
            urdf_pose = expected[link_name]
            position_error = float(np.linalg.norm(np.array(urdf_pose.position) - position))
            rotation = matrix3((float(v) for v in row) for row in matrix.reshape(3, 3))
            rotation_error = rotation_angle_between(urdf_pose.rotation, rotation)
            error = LinkError(link_name, position_error, rotation_error, number)
            worst = result.worst
            if worst is None or max(position_error, rotation_error) > max(
                worst.position, worst.rotation
            ):
                result.worst = error
            known = result.per_link.get(link_name)
            if known is None or max(position_error, rotation_error) > max(
                known.position, known.rotation
            ):
                result.per_link[link_name] = error
            result.max_position = max(result.max_position, position_error)
            result.max_rotation = max(result.max_rotation, rotation_error)
    return result


def _resting(model, joint: int, expected: dict) -> list[float]:
    """The free joint ``joint``'s qpos that puts its body where ``expected`` (the URDF's link
    poses) has the link of its name: identity where it has none."""
    import mujoco
    import numpy as np

    pose = expected.get(model.body(model.jnt_bodyid[joint]).name)
    if pose is None:
        return [0, 0, 0, 1, 0, 0, 0]
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.array(pose.rotation, dtype=float).reshape(9))
    return [*pose.position, *quat]


def _root_first(robot: Robot) -> list[str]:
    """Link names, breadth first from the root."""
    children = robot.child_joints()
    order = [robot.root]
    for name in order:
        order += [joint.child for joint in children[name]]
    return order
