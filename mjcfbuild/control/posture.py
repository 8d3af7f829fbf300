"""A standing pose for a floating robot whose description gives none that stands.

Most quadruped URDFs are drawn with straight legs, or with knees clipped into their range so
the feet end up ahead of the hips, and the robot tips over from that pose. When neither
robot.yaml nor an SRDF gives a home and the robot falls from the zero pose, the build
computes a crouch: every foot on the floor under its leg's first joint (the hip), the leg
shortened to :data:`CROUCH` of its length at zero, the base level, each joint as close to its
zero pose as that allows and within its limits. It is solved per leg by damped least squares
on the foot's position, with the base held; the build then simulates it, and keeps it only if
the robot stands there (see :func:`mjcfbuild.mjcf.assemble` and docs/simulation.md).
"""

from __future__ import annotations

CROUCH = 0.8  # a standing leg's hip-to-foot length, as a share of its length at zero
ITERATIONS = 200
DAMPING = 1e-3


def crouch_pose(model, data, feet: dict[int, list[float]]) -> dict[str, float]:
    """Joint positions (by name) that put each foot of ``feet`` (body -> its lowest point in
    ``data``'s pose, kinematics computed) under its hip, crouched; only joints of the legs."""
    import mujoco
    import numpy as np

    qpos = data.qpos.copy()
    work = mujoco.MjData(model)
    result: dict[str, float] = {}
    for body, point in feet.items():
        chain = _chain(model, body)
        if not chain:
            continue
        local = _to_body(data, body, np.asarray(point, dtype=float))
        hip = np.asarray(data.xanchor[chain[0]], dtype=float)
        target = np.array([hip[0], hip[1], hip[2] - CROUCH * (hip[2] - point[2])])
        dofs = [int(model.jnt_dofadr[j]) for j in chain]
        addresses = [int(model.jnt_qposadr[j]) for j in chain]
        work.qpos[:] = qpos
        jacobian = np.zeros((3, model.nv))
        # Bend each knee-like joint a little first: straight legs give no vertical gradient.
        for joint, address in zip(chain, addresses, strict=True):
            bent = work.qpos[address] + 0.05 * _bend(model, joint)
            work.qpos[address] = _clip(model, joint, bent)
        for _ in range(ITERATIONS):
            mujoco.mj_kinematics(model, work)
            mujoco.mj_comPos(model, work)
            foot = work.xpos[body] + work.xmat[body].reshape(3, 3) @ local
            error = target - foot
            if float(np.linalg.norm(error)) < 1e-4:
                break
            mujoco.mj_jac(model, work, jacobian, None, foot, body)
            columns = jacobian[:, dofs]
            step = columns.T @ np.linalg.solve(columns @ columns.T + DAMPING * np.eye(3), error)
            for joint, address, change in zip(chain, addresses, step, strict=True):
                work.qpos[address] = _clip(model, joint, work.qpos[address] + change)
        for joint, address in zip(chain, addresses, strict=True):
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
            if name:
                result[name] = float(work.qpos[address])
    return result


def _chain(model, body: int) -> list[int]:
    """The hinge and slide joints from the floating base down to ``body``, base first."""
    import mujoco

    joints = []
    while body > 0:
        first = int(model.body_jntadr[body])
        for joint in range(first, first + int(model.body_jntnum[body])):
            if mujoco.mjtJoint(model.jnt_type[joint]) in (
                mujoco.mjtJoint.mjJNT_HINGE,
                mujoco.mjtJoint.mjJNT_SLIDE,
            ):
                joints.append(joint)
        body = int(model.body_parentid[body])
    return joints[::-1]


def _to_body(data, body: int, point):
    rotation = data.xmat[body].reshape(3, 3)
    return rotation.T @ (point - data.xpos[body])


def _bend(model, joint: int) -> float:
    """+1 or -1: the direction into the joint's range from the middle, or +1 when unlimited."""
    if not model.jnt_limited[joint]:
        return 1.0
    low, high = model.jnt_range[joint]
    return 1.0 if abs(high) >= abs(low) else -1.0


def _clip(model, joint: int, value: float) -> float:
    if not model.jnt_limited[joint]:
        return float(value)
    low, high = model.jnt_range[joint]
    return float(min(max(value, low), high))
