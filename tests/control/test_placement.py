"""The scene's floor under a fixed-base robot: lowered automatically, or warned about."""

from __future__ import annotations

import mujoco
import pytest

import mjcfbuild
from tests.conftest import two_link_urdf, write
from tests.control.helpers import build_two_link


def _floor_height(result) -> float:
    model = mujoco.MjModel.from_xml_path(str(result.scene))
    floor = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "floor")
    return float(model.geom_pos[floor][2])


def test_the_floor_goes_under_a_robot_that_reaches_below_zero(tmp_path):
    # The base box (0.1 m tall) is centred on the base frame, at the world origin.
    result = build_two_link(tmp_path)
    assert _floor_height(result) == pytest.approx(-0.05, abs=1e-9)
    assert not any("below the scene's floor" in w for w in result.warnings)


def test_a_floor_set_above_the_robot_is_warned_about(tmp_path):
    # The check would fail too: the robot starts inside the floor.
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\nplacement: {floor: 0.2}\n",
    )
    result = mjcfbuild.build(tmp_path / "robot.yaml", check=False)
    assert _floor_height(result) == pytest.approx(0.2)
    assert any(
        "reaches 0.25 m below the scene's floor; set placement: {floor: auto}" in w
        for w in result.warnings
    ), result.warnings
