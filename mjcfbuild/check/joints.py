"""Joint types, axes and ranges of the model against the URDF's."""

from __future__ import annotations

import math

import numpy as np

from mjcfbuild.check.findings import Problem
from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.limits import joint_range
from mjcfbuild.urdf.model import Robot
from mjcfbuild.urdf.transforms import apply, vec3

EXPECTED_TYPES = {
    "revolute": "hinge",
    "continuous": "hinge",
    "prismatic": "slide",
    "floating": "free",
}


def compare_joints(robot: Robot, model, tolerance: float = 1e-6) -> list[Problem]:
    """Problems with the model's joints, each naming the joint and the numbers.

    A missing joint or one of another type is structural. Axes (unit vectors) and ranges are
    compared relative to their size: ``tolerance`` times the larger of 1 and the value.
    """
    import mujoco

    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    poses = link_poses(robot)
    problems = []
    for joint in robot.joints:
        expected = EXPECTED_TYPES.get(joint.kind)
        if expected is None:
            continue
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint.name)
        if index < 0:
            problems.append(
                Problem(f"joint '{joint.name}' ({joint.kind}) is missing from the model", True)
            )
            continue
        kind = mujoco.mjtJoint(model.jnt_type[index]).name.removeprefix("mjJNT_").lower()
        if kind != expected:
            problems.append(
                Problem(
                    f"joint '{joint.name}': {joint.kind} in the URDF, {kind} in the model", True
                )
            )
            continue
        if kind == "free":
            continue
        # Axes in world coordinates at the zero configuration, so any body frame convention works.
        norm = math.sqrt(sum(a * a for a in joint.axis))
        urdf_axis = np.array(apply(poses[joint.child].rotation, vec3(a / norm for a in joint.axis)))
        model_axis = data.xaxis[index]
        if np.linalg.norm(urdf_axis - model_axis) > tolerance:
            problems.append(
                Problem(
                    f"joint '{joint.name}': axis {_vector(urdf_axis)} in the URDF, "
                    f"{_vector(model_axis)} in the model (world frame, zero configuration)"
                )
            )
        limited = bool(model.jnt_limited[index])
        bounds = joint_range(joint)
        if bounds is None:
            if limited:
                problems.append(
                    Problem(
                        f"joint '{joint.name}' is unlimited in the URDF but has range "
                        f"{_vector(model.jnt_range[index])} in the model"
                    )
                )
            continue
        if bounds[1] > bounds[0]:  # a locked joint's tiny range is the build's own choice
            expected_range = np.array(bounds)
            allowed = tolerance * np.maximum(1.0, np.abs(expected_range))
            if not limited or np.any(np.abs(model.jnt_range[index] - expected_range) > allowed):
                shown = _vector(model.jnt_range[index]) if limited else "no range"
                problems.append(
                    Problem(
                        f"joint '{joint.name}': range {_vector(expected_range)} in the URDF, "
                        f"{shown} in the model"
                    )
                )
    return problems


def _vector(values) -> str:
    return "(" + ", ".join(f"{float(v):.6g}" for v in values) + ")"
