"""How mujoco_ros2_control finds a model's actuators by name, as its source does.

Two lookups, which disagree: ``get_actuator_id`` (:func:`actuator_of`) takes a joint's name for
the actuator driving the joint, else an actuator's own name; the actuator data
``register_mujoco_actuators`` makes (:func:`registered`) is searched by the name of the joint
each entry stands for: a joint actuator's joint, a tendon or site actuator's own name, and one
passive entry for every hinge or slide joint no actuator drives.
"""

from __future__ import annotations

from typing import Literal

# The actuator transmissions register_mujoco_actuators takes; any other stops it ("Unsupported
# transmission type").
_SUPPORTED = ("mjTRN_JOINT", "mjTRN_TENDON", "mjTRN_SITE")


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

    entries = _entries(model)
    if any(joint == name for _, joint, _ in entries):
        return "actuator"
    driven = {int(model.jnt_qposadr[target]) for _, _, target in entries if target >= 0}
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
    moving = (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)
    if index >= 0 and model.jnt_type[index] in moving and model.jnt_qposadr[index] not in driven:
        return "passive"
    return None


def transmission_actuator(model, names: list[str]) -> tuple[int, str] | None:
    """The actuator register_urdf_joints gives a joint driven only through a transmission of
    actuators ``names``: the first entry of its actuator data whose MJCF actuator or joint has
    one of the names; with the joint name the runtime reads its PID gains under."""
    import mujoco

    for name in names:
        for actuator, joint, _ in _entries(model):
            if name in (joint, mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, actuator)):
                return actuator, joint
    return None


def site_entry(model, name: str) -> tuple[str, int] | None:
    """Where the first entry of the runtime's actuator data under ``name`` (the one
    register_transmissions takes for a transmission actuator of that name) is a site actuator's:
    the site's name and the index of the joint whose state the runtime reads for it, which
    register_mujoco_actuators takes from the site's index (``jnt_qposadr[site]``; at or past
    ``njnt`` a read past the model's joints)."""
    import mujoco

    for actuator, joint, _ in _entries(model):
        if joint != name:
            continue
        if model.actuator_trntype[actuator] != mujoco.mjtTrn.mjTRN_SITE:
            return None
        site = int(model.actuator_trnid[actuator, 0])
        return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SITE, site) or f"#{site}", site
    return None


def _entries(model) -> list[tuple[int, str, int]]:
    """The actuator data register_mujoco_actuators makes of the model's actuators: each
    actuator, the joint name it stands for (a joint actuator's joint, a tendon or site
    actuator's own name) and the joint whose qpos it reads (-1 where none)."""
    import mujoco

    entries = []
    for actuator in range(model.nu):
        trn = model.actuator_trntype[actuator]
        target = int(model.actuator_trnid[actuator, 0])
        own = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, actuator) or "unnamed"
        if trn == mujoco.mjtTrn.mjTRN_JOINT:
            joint = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, target) or ""
        elif trn == mujoco.mjtTrn.mjTRN_TENDON:
            joint, target = own, mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, own)
        else:
            joint = own  # a site's: the runtime reads the qpos of the joint of the site's index
        entries.append((actuator, joint, target if 0 <= target < model.njnt else -1))
    return entries


def unsupported_transmissions(model) -> list[str]:
    """One failure per actuator whose transmission the runtime does not take (slider-crank,
    joint-in-parent, body): register_mujoco_actuators stops at start-up."""
    import mujoco

    supported = {int(getattr(mujoco.mjtTrn, name)) for name in _SUPPORTED}
    failures = []
    for index in range(model.nu):
        trn = int(model.actuator_trntype[index])
        if trn in supported:
            continue
        name = model.actuator(index).name or f"#{index}"
        kind = mujoco.mjtTrn(trn).name.removeprefix("mjTRN_").lower()
        failures.append(
            f"actuator '{name}' has a {kind} transmission, which mujoco_ros2_control does not "
            'take: it stops at start-up ("Unsupported transmission type"); drive a joint, a '
            "tendon or a site instead"
        )
    return failures


def unnamed_joints(model) -> list[str]:
    """A failure where the model has joints without a name, other than free ones: the runtime
    stops at start-up ("All non-free joints must have names")."""
    import mujoco

    unnamed = [
        index
        for index in range(model.njnt)
        if not model.joint(index).name and model.jnt_type[index] != mujoco.mjtJoint.mjJNT_FREE
    ]
    if not unnamed:
        return []
    bodies = _first([model.body(int(model.jnt_bodyid[index])).name or "?" for index in unnamed])
    return [
        f"{len(unnamed)} joint{'s' if len(unnamed) > 1 else ''} of the model (in bod"
        f"{'ies' if len(unnamed) > 1 else 'y'} {bodies}) {'have' if len(unnamed) > 1 else 'has'} "
        'no name: mujoco_ros2_control stops at start-up ("All non-free joints must have '
        'names"); name them'
    ]


def _first(names: list[str]) -> str:
    return ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
