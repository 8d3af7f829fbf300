"""MuJoCo Warp loads default builds and steps several worlds without NaN (slow: Warp compiles
its kernels on first use)."""

from __future__ import annotations

import pytest

import mjcfbuild
from bench import robot_data
from mjcfbuild.check.warp import check_in_warp
from tests.conftest import run_cli

pytest.importorskip("mujoco_warp")
pytestmark = pytest.mark.slow


def test_the_example_arm_runs_in_warp_from_the_command_line(arm):
    assert run_cli("build", str(arm / "robot.yaml")).code == 0
    result = run_cli("check", "--warp", str(arm / "robot.yaml"))
    assert result.code == 0, result.stderr
    assert "MuJoCo Warp: 4 worlds, 50 steps, finite" in result.stdout


@pytest.mark.robots
def test_a_quadruped_runs_in_warp(tmp_path):
    robot = robot_data.ROBOTS["go1"]
    urdf = robot_data.unpack(robot)
    result = mjcfbuild.build(robot_data.manifest(robot, tmp_path, urdf, robot_data.package_root()))
    warp = check_in_warp(str(result.scene), worlds=4, steps=50)
    assert warp.finite
