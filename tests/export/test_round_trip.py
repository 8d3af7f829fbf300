"""URDF -> MJCF -> URDF on the real robots, built with static links kept as bodies of their own
(tests/robots/test_real_robots.py round-trips the default, fused builds it makes anyway)."""

from __future__ import annotations

import pytest

import mjcfbuild
from bench import robot_data
from tests.export.round_trip import EXPORT, assert_round_trip

pytestmark = [pytest.mark.robots, pytest.mark.slow]


@pytest.mark.parametrize("name", sorted(robot_data.ROBOTS))
def test_round_trip_of_an_unfused_build_keeps_link_poses_and_masses(name, tmp_path):
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(
        robot, tmp_path, urdf, robot_data.package_root(), extra=EXPORT, fuse_static=False
    )
    result = mjcfbuild.build(manifest, jobs=2, check=False)
    assert_round_trip(urdf, result.robot, fuse_static=False)
