"""How mujoco_ros2_control finds a model's actuators by name, as its source does."""

from __future__ import annotations


def actuator_of(model, joint: str) -> int:
    """The actuator the runtime finds for ``joint``: one on the joint, else one of its name
    (a tendon's, say); -1 where there is none."""
    import mujoco

    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
    if index >= 0:
        for actuator in range(model.nu):
            trn = model.actuator_trntype[actuator]
            if trn == mujoco.mjtTrn.mjTRN_JOINT and model.actuator_trnid[actuator, 0] == index:
                return actuator
    return mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, joint)
