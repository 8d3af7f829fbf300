"""How mujoco_ros2_control finds a model's actuators by name, as its source does.

Two lookups, which disagree: ``get_actuator_id`` (:func:`actuator_of`) takes a joint's name for
the actuator driving the joint, else an actuator's own name; the actuator data
``register_mujoco_actuators`` makes (:func:`registered`) is searched by the name of the joint
each entry stands for: a joint actuator's joint, a tendon or site actuator's own name, and one
passive entry for every hinge or slide joint no actuator drives.
"""

from __future__ import annotations

from typing import Literal


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


def registered(model, name: str) -> Literal["actuator", "passive"] | None:
    """What the runtime's actuator data holds under ``name``: the first entry standing for a
    joint of that name, an actuator's ('actuator') or an undriven joint's ('passive'); None
    where no entry does."""
    import mujoco

    driven: set[int] = set()
    for actuator in range(model.nu):
        trn = model.actuator_trntype[actuator]
        target = int(model.actuator_trnid[actuator, 0])
        own = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, actuator) or "unnamed"
        if trn == mujoco.mjtTrn.mjTRN_JOINT:
            joint = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, target)
        elif trn == mujoco.mjtTrn.mjTRN_TENDON:
            joint, target = own, mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, own)
        else:
            joint = own
        if joint == name:
            return "actuator"
        if 0 <= target < model.njnt:
            driven.add(int(model.jnt_qposadr[target]))
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
    moving = (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)
    if index >= 0 and model.jnt_type[index] in moving and model.jnt_qposadr[index] not in driven:
        return "passive"
    return None
