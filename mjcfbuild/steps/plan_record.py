"""``plan.json``: what the ``plan`` step found, written and read here only.

The plan decides the rest of the graph (one mesh task per planned mesh) and carries the parsed
robot, the MuJoCo inputs and the ros2_control of the URDF (and of the inputs file) to the
steps after it.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mjcfbuild.records import Record

if TYPE_CHECKING:
    from mjcfbuild.inputs.gazebo import GazeboSensor
    from mjcfbuild.inputs.ros2_control import Ros2Control
    from mjcfbuild.urdf.model import Robot


@dataclass(frozen=True)
class PlannedMesh(Record):
    """A mesh file to convert, by its id (the task's name) and absolute path."""

    id: str
    path: str
    # convert -a: the mesh file a pre-generated OBJ stands for, whose look it takes where it
    # has none of its own (meshes.prebuilt)
    looks_from: str | None = None


@dataclass(frozen=True)
class PlannedInputs(Record):
    """The MuJoCo inputs found in the URDF, and in the inputs file if there is one."""

    urdf: dict[str, Any]
    file: dict[str, Any] | None

    def get(self, where: str) -> dict[str, Any] | None:
        """The inputs of ``where`` (``urdf`` or ``file``)."""
        found: dict[str, Any] | None = getattr(self, where)
        return found


@dataclass(frozen=True)
class Plan(Record):
    """The build plan."""

    robot: dict[str, Any]  # urdf.model.Robot.to_dict()
    meshes: list[PlannedMesh]
    inputs: PlannedInputs
    ros2_control: dict[str, Any]  # inputs.ros2_control.Ros2Control.to_dict()
    gazebo_sensors: list[dict[str, Any]] = dataclasses.field(default_factory=list)

    def robot_model(self) -> Robot:
        """The parsed robot."""
        from mjcfbuild.urdf.model import robot_from_dict

        return robot_from_dict(self.robot)

    def control(self) -> Ros2Control:
        """The ros2_control of the URDF."""
        from mjcfbuild.inputs.ros2_control import Ros2Control

        return Ros2Control.from_dict(self.ros2_control)

    def gazebo(self) -> list[GazeboSensor]:
        """The Gazebo sensors of the URDF."""
        from mjcfbuild.inputs.gazebo import GazeboSensor

        return [GazeboSensor(**sensor) for sensor in self.gazebo_sensors]

    def text(self) -> bytes:
        """The plan as the bytes of ``plan.json``."""
        return (json.dumps(self.to_dict(), indent=1, sort_keys=True) + "\n").encode()


def read_plan(path: Path) -> Plan:
    """The plan in ``path``."""
    return Plan.from_dict(json.loads(path.read_text()))
