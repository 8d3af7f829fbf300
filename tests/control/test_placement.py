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


def _drawn_only(folder, floor: str = "auto"):
    """The two-link robot with its collision shapes made visual ones: nothing collides."""
    urdf = two_link_urdf().replace("<collision>", "<visual>").replace("</collision>", "</visual>")
    write(folder / "robot.urdf", urdf)
    write(
        folder / "robot.yaml",
        f"name: r\nsource: {{urdf: robot.urdf}}\nplacement: {{floor: {floor}}}\n",
    )
    return mjcfbuild.build(folder / "robot.yaml", check=False)


def test_the_floor_goes_under_what_a_robot_without_collision_geometry_draws(tmp_path):
    # The floor stayed at z = 0, through the drawn base box (0.05 m below), with no word.
    result = _drawn_only(tmp_path)
    assert _floor_height(result) == pytest.approx(-0.05, abs=1e-9)
    assert not any("below the scene's floor" in w for w in result.warnings)


def test_a_floor_set_above_what_a_robot_without_collision_geometry_draws_is_warned_about(
    tmp_path,
):
    result = _drawn_only(tmp_path, "0.2")
    assert _floor_height(result) == pytest.approx(0.2)
    assert any(
        "reaches 0.25 m below the scene's floor (its visual geometry: nothing of the model "
        "collides); set placement: {floor: auto}" in w
        for w in result.warnings
    ), result.warnings
