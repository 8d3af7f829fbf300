"""Building small robots for the control tests."""

from __future__ import annotations

import json
from pathlib import Path

import mujoco

import mjcfbuild
from tests.conftest import two_link_urdf, write


def build_two_link(folder: Path, manifest_extra: str = "", urdf_extra: str = "", **urdf):
    """Build the two-link robot with ``manifest_extra`` in its robot.yaml; the build result."""
    write(folder / "robot.urdf", two_link_urdf(extra=urdf_extra, **urdf))
    write(folder / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + manifest_extra)
    result = mjcfbuild.build(folder / "robot.yaml")
    assert not result.errors, result.errors
    return result


def load(result) -> mujoco.MjModel:
    """The built robot model."""
    return mujoco.MjModel.from_xml_path(str(result.robot))


def readiness(folder: Path) -> dict:
    """What the build recorded about actuators and home."""
    return json.loads((folder / "mjcf/.mjcfbuild/assembly.json").read_text())["readiness"]


def actuator(model, name: str) -> int:
    """The id of actuator ``name`` (which must exist)."""
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
    assert index >= 0, f"no actuator {name}"
    return index
