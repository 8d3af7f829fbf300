"""Making a floating robot stand when its description gives no pose it stands in.

Run after :func:`~mjcfbuild.control.apply.make_ready` on a robot whose home came from nothing
(every joint at zero, clipped into its range): the finished tree is simulated on a floor for
:data:`TRIAL_SECONDS` holding home; if the robot falls, a crouch is computed
(:mod:`mjcfbuild.control.posture`), the tree made ready again from a copy taken before, and
simulated again. The crouch is kept only if the robot stands in it; otherwise the first tree
stays and the check says what to write.
"""

from __future__ import annotations

from collections.abc import Callable
from copy import deepcopy
from dataclasses import replace
from typing import Any

from lxml import etree

from mjcfbuild.control.apply import Readiness
from mjcfbuild.control.home import HomeValue

TRIAL_SECONDS = 3.0


def described_nothing(home: list[HomeValue]) -> bool:
    """Whether no joint's home came from robot.yaml, an SRDF, ros2_control or a part."""
    return all(value.source in ("zero", "mimic") for value in home)


def stands(root: etree._Element, compile_tree: Callable[[etree._Element], Any]) -> bool:
    """Whether the robot of ``root`` (with its home keyframe) stands on a floor holding home."""
    import mujoco

    from mjcfbuild.control.stand_test import stand_test
    from mjcfbuild.mjstopped import simulating

    trial = deepcopy(root)
    worldbody = trial.find("worldbody")
    if worldbody is None:
        return False
    etree.SubElement(
        worldbody, "geom", {"name": "mjcfbuild_trial_floor", "type": "plane", "size": "0 0 0.05"}
    )
    model = compile_tree(trial)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if key < 0:
        return True  # the user's own keyframe: nothing to decide here
    with simulating(f"the build's {TRIAL_SECONDS:g} s trial of whether the robot stands at home"):
        result = stand_test(model, key, set(), TRIAL_SECONDS)
    return not result.needs_controller and not result.fails(float("inf"))


def crouched_home(
    root: etree._Element,
    compile_tree: Callable[[etree._Element], Any],
    home: list[HomeValue],
    readiness: Readiness,
) -> list[HomeValue] | None:
    """Home with every leg crouched under its hip (source ``computed``), from the finished
    tree's stance at home; None when it has no feet on the floor."""
    import mujoco

    from mjcfbuild.control.floor import geom_lowest_points
    from mjcfbuild.control.posture import crouch_pose

    stance = readiness.stance or {}
    if not stance.get("feet"):
        return None
    model = compile_tree(root)
    data = mujoco.MjData(model)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    mujoco.mj_resetDataKeyframe(model, data, key)
    mujoco.mj_forward(model, data)

    feet: dict[int, list[float]] = {}
    names = set(stance["feet"])
    for geom, point in geom_lowest_points(model, data).items():
        body = int(model.geom_bodyid[geom])
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body)
        if name in names and (body not in feet or point[2] < feet[body][2]):
            feet[body] = [float(v) for v in point]
    pose = crouch_pose(model, data, feet)
    if not pose:
        return None
    return [
        replace(value, value=pose[value.joint], source="computed") if value.joint in pose else value
        for value in home
    ]


def replace_tree(root: etree._Element, other: etree._Element) -> None:
    """Make ``root`` hold ``other``'s children and attributes."""
    root[:] = list(other)
    root.attrib.clear()
    root.attrib.update(other.attrib)
