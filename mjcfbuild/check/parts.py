"""Each MJCF part of the built model against the part compiled alone.

The reference is the part's own file loaded and compiled by MuJoCo, untouched by the build.
At the part's qpos0 and at random configurations of its joints, every body of the part must
sit, relative to its attachment frame (the ``to`` link, then the part's offset), where the
part alone puts it relative to its world; its joints must have the same type and range, and
its bodies the same mass.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from pathlib import Path

from mjcfbuild.compose.part_names import joint_names
from mjcfbuild.urdf.transforms import rotation_angle_between


@dataclass(frozen=True)
class PartReference:
    """An attached MJCF part, as the check finds it in the built model."""

    prefix: str
    source: Path  # the part's own file
    label: str
    to: str
    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]


@dataclass
class PartResult:
    """How far the built part is from the part alone."""

    label: str
    configurations: int
    max_position_error: float = 0.0
    max_rotation_error: float = 0.0
    worst_body: str | None = None
    missing: list[str] = field(default_factory=list)  # bodies or joints not in the model
    problems: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return dict(self.__dict__)


def check_part(
    model, part: PartReference, configurations: int, seed: int, tolerance: float
) -> PartResult:
    """Compare the part's bodies, joints and masses in ``model`` (the built MjModel) with
    the part compiled alone; ``tolerance`` is in m and rad, and relative for masses."""
    import mujoco
    import numpy as np

    from mjcfbuild.mjcache import forget_earlier_builds

    forget_earlier_builds()  # the part's files are the user's
    alone = mujoco.MjModel.from_xml_path(str(part.source))
    result = PartResult(part.label, configurations)
    obj = mujoco.mjtObj

    def named(kind, m, i: int) -> str:
        return mujoco.mj_id2name(m, kind, i) or ""

    bodies = {}
    for body in range(1, alone.nbody):
        name = named(obj.mjOBJ_BODY, alone, body)
        found = mujoco.mj_name2id(model, obj.mjOBJ_BODY, part.prefix + name) if name else -1
        if found < 0:
            result.missing.append(f"body '{part.prefix}{name}'")
        else:
            bodies[body] = found
    joints = {}
    # An unnamed joint of the part has the name the build gave it (compose.mjcf.joint_names).
    given = joint_names(
        [
            (named(obj.mjOBJ_JOINT, alone, j), named(obj.mjOBJ_BODY, alone, alone.jnt_bodyid[j]))
            for j in range(alone.njnt)
        ]
    )
    for joint in range(alone.njnt):
        name = given[joint]
        found = mujoco.mj_name2id(model, obj.mjOBJ_JOINT, part.prefix + name) if name else -1
        if found < 0:
            result.missing.append(f"joint '{part.prefix}{name}'")
            continue
        joints[joint] = found
        result.problems += _joint_problems(alone, model, joint, found, part.prefix + name)
    for body, found in bodies.items():
        mass, built = float(alone.body_mass[body]), float(model.body_mass[found])
        if abs(mass - built) > tolerance * max(mass, 1e-12) + 1e-12:
            name = named(obj.mjOBJ_BODY, model, found)
            result.problems.append(f"body '{name}': mass {built:.9g}, {mass:.9g} alone")
    frame = _attachment_frame(model, part)
    if frame is None:
        result.missing.append(f"attachment link '{part.to}'")
        return result
    data_alone, data = mujoco.MjData(alone), mujoco.MjData(model)
    rng = random.Random(seed)
    for number in range(configurations):
        data_alone.qpos[:] = alone.qpos0
        data.qpos[:] = model.qpos0
        if number > 0:
            for joint, found in joints.items():
                values = _random_position(alone, joint, rng)
                start, end = _qpos_span(alone, joint)
                data_alone.qpos[start:end] = values
                built_start = model.jnt_qposadr[found]
                data.qpos[built_start : built_start + end - start] = values
        mujoco.mj_kinematics(alone, data_alone)
        mujoco.mj_kinematics(model, data)
        rotation, position = frame(data)
        for body, found in bodies.items():
            expected_position = position + rotation @ data_alone.xpos[body]
            expected_rotation = rotation @ data_alone.xmat[body].reshape(3, 3)
            error = float(np.linalg.norm(data.xpos[found] - expected_position))
            angle = rotation_angle_between(
                _rows(data.xmat[found].reshape(3, 3)), _rows(expected_rotation)
            )
            if max(error, angle) > max(result.max_position_error, result.max_rotation_error):
                result.worst_body = named(obj.mjOBJ_BODY, model, found)
            result.max_position_error = max(result.max_position_error, error)
            result.max_rotation_error = max(result.max_rotation_error, angle)
    return result


def _rows(matrix) -> tuple:
    return tuple(tuple(float(v) for v in row) for row in matrix)


def _attachment_frame(model, part: PartReference):
    """A function of MjData giving the attachment frame's world rotation and position."""
    import mujoco
    import numpy as np

    offset_rotation = np.zeros(9)
    mujoco.mju_quat2Mat(offset_rotation, np.array(part.quat, dtype=float))
    offset = (offset_rotation.reshape(3, 3), np.array(part.pos, dtype=float))
    body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, part.to)
    site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, part.to)
    if body < 0 and site < 0:
        return None

    def frame(data):
        if body >= 0:
            rotation, position = data.xmat[body].reshape(3, 3), data.xpos[body]
        else:
            rotation, position = data.site_xmat[site].reshape(3, 3), data.site_xpos[site]
        return rotation @ offset[0], position + rotation @ offset[1]

    return frame


def _joint_problems(alone, model, joint: int, found: int, name: str) -> list[str]:
    problems = []
    if alone.jnt_type[joint] != model.jnt_type[found]:
        problems.append(f"joint '{name}' has another type than in the part alone")
    if bool(alone.jnt_limited[joint]) != bool(model.jnt_limited[found]):
        problems.append(f"joint '{name}' is limited in one model and not the other")
    elif alone.jnt_limited[joint]:
        expected, built = alone.jnt_range[joint], model.jnt_range[found]
        if any(abs(a - b) > 1e-9 * max(1.0, abs(a)) for a, b in zip(expected, built, strict=True)):
            problems.append(
                f"joint '{name}': range [{built[0]:.9g}, {built[1]:.9g}], "
                f"[{expected[0]:.9g}, {expected[1]:.9g}] alone"
            )
    return problems


def _qpos_span(model, joint: int) -> tuple[int, int]:
    import mujoco

    size = {int(mujoco.mjtJoint.mjJNT_FREE): 7, int(mujoco.mjtJoint.mjJNT_BALL): 4}
    start = int(model.jnt_qposadr[joint])
    return start, start + size.get(int(model.jnt_type[joint]), 1)


def _random_position(model, joint: int, rng: random.Random) -> list[float]:
    """A position of ``joint`` within its range (a ball joint: a random rotation)."""
    import mujoco

    kind = model.jnt_type[joint]
    if kind == mujoco.mjtJoint.mjJNT_BALL:
        quat = [rng.gauss(0.0, 1.0) for _ in range(4)]
        norm = math.sqrt(sum(q * q for q in quat))
        return [q / norm for q in quat]
    if model.jnt_limited[joint]:
        low, high = (float(v) for v in model.jnt_range[joint])
    elif kind == mujoco.mjtJoint.mjJNT_SLIDE:
        low, high = -0.5, 0.5
    else:
        low, high = -math.pi, math.pi
    return [rng.uniform(low, high)]
