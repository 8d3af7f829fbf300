"""Speed limits known outside the model: a URDF's ``<limit velocity>`` per joint.

MJCF has no velocity limit; where a model's actuators do not give a joint's top speed
(:func:`mjcfbuild.export.reader.joint_speed`), the URDF the model was made from may."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import unreadable_file

if TYPE_CHECKING:
    from mjcfbuild.urdf.model import Robot


def urdf_speeds(robot: Robot) -> dict[str, float]:
    """Joint name -> the URDF's velocity limit, where it gives a real one (0 and -1 are
    placeholders that descriptions in the wild use for 'unknown')."""
    speeds = {}
    for joint in robot.joints:
        velocity = joint.limit.velocity if joint.limit is not None else None
        if velocity is not None and velocity > 0 and math.isfinite(velocity):
            speeds[joint.name] = float(velocity)
    return speeds


def read_urdf_speeds(path: Path) -> dict[str, float]:
    """The velocity limits of the URDF file at ``path``; :class:`InputError` naming the file
    (and line) where it cannot be read or parsed."""
    from mjcfbuild.urdf.parse import parse_urdf

    problem = unreadable_file(path)
    if problem:
        raise InputError(f"URDF file {problem}", file=path)
    return urdf_speeds(parse_urdf(path.read_bytes(), str(path)))
