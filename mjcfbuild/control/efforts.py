"""Telling a floating robot's placeholder effort limits from real ones, and what to use instead.

Some descriptions give every joint the same large effort (solo12: 1000 N m on a 2.5 kg robot)
because the URDF requires a number. Real legged robots' and humanoids' joint efforts lie between
about 0.04 and 16 times the torque that holds the whole robot's weight at the joint's reach (the
farthest its moving bodies are from the axis); solo12's are 125 to 255 times it. A servo with
such a limit whips a light leg around at hundreds of rad/s under full-range commands, and the
simulation goes unstable. When every effort-limited joint of a floating robot is past
:data:`PLACEHOLDER_RATIO`, the efforts are taken for placeholders and each force range is set to
the joint's holding load (about what real legged robots' motors give: solo12's give 2.7 N m
where its holding loads are 3.9 to 8.0 N m), and the build says so.
"""

from __future__ import annotations

from dataclasses import dataclass

# An effort this many times the joint's holding torque is a placeholder (real robots: <= 16).
PLACEHOLDER_RATIO = 50.0


@dataclass(frozen=True)
class EffortCap:
    """A joint whose URDF effort was taken for a placeholder: the effort and its new limit."""

    joint: str
    effort: float
    holding: float  # the torque (N m) or force (N) that holds the whole robot at the joint


def holding_load(model, data, joint: int) -> float:
    """The torque (hinge, N m) or force (slide, N) that holds the whole robot's weight at
    ``joint``'s reach in ``data``'s pose; 0 for other joint types."""
    import mujoco
    import numpy as np

    weight = float(model.body_subtreemass[0]) * float(np.linalg.norm(model.opt.gravity))
    kind = model.jnt_type[joint]
    if kind == mujoco.mjtJoint.mjJNT_SLIDE:
        return weight
    if kind != mujoco.mjtJoint.mjJNT_HINGE:
        return 0.0
    moving = subtree(model, int(model.jnt_bodyid[joint]))
    points = [data.xipos[body] for body in moving]
    points += [
        data.geom_xpos[geom] for geom in range(model.ngeom) if model.geom_bodyid[geom] in moving
    ]
    anchor, axis = data.xanchor[joint], data.xaxis[joint]
    reach = max(float(np.linalg.norm(np.cross(point - anchor, axis))) for point in points)
    return weight * reach


def placeholder_efforts(model, data, efforts: dict[str, float]) -> list[EffortCap]:
    """The caps for a floating robot's ``efforts`` (joint name -> URDF effort) at ``data``'s
    pose, if every one of them is a placeholder; else none."""
    import mujoco

    caps = []
    for name, effort in efforts.items():
        joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        holding = holding_load(model, data, joint) if joint >= 0 else 0.0
        if holding <= 0 or effort <= PLACEHOLDER_RATIO * holding:
            return []
        caps.append(EffortCap(name, effort, holding))
    return caps


def describe(caps: list[EffortCap]) -> str:
    """The build's warning about ``caps``."""
    efforts = _span([cap.effort for cap in caps], "g")
    ratios = [cap.effort / cap.holding for cap in caps]
    holdings = _span([cap.holding for cap in caps], ".3g")
    return (
        f"the URDF's effort limits look like placeholders: on all {len(caps)} actuated joints "
        f"the effort ({efforts}) is {min(ratios):.0f}-{max(ratios):.0f} times the load that "
        "holds the whole robot at the joint (real robots: at most 16), so each force range is "
        f"that holding load ({holdings}); give the real limits with rules' forceranges, e.g. "
        'actuators: {rules: [{joints: ["*"], forcerange: [-N, N]}]}'
    )


def _span(values: list[float], style: str) -> str:
    low, high = format(min(values), style), format(max(values), style)
    return low if low == high else f"{low}-{high}"


def subtree(model, root: int) -> set[int]:
    """``root`` and every body below it."""
    bodies = {root}
    for body in range(root + 1, model.nbody):
        if int(model.body_parentid[body]) in bodies:
            bodies.add(body)
    return bodies
