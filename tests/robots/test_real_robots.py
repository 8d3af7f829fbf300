"""The real robots of example-robot-data build with default settings, load, simulate, and
put every URDF link where the URDF does (checked by code independent of MuJoCo's import).

The wheel is downloaded once into a cache (see bench/robot_data.py). Run only these with
``pytest -m robots``; skip them with ``-m "not robots"``.
"""

from __future__ import annotations

import json

import mujoco
import numpy as np
import pytest

import mjcfbuild
from bench import robot_data
from mjcfbuild.check.kinematics import compare_kinematics
from mjcfbuild.urdf.parse import parse_urdf

pytestmark = [pytest.mark.robots, pytest.mark.slow]


NAMES = sorted(robot_data.ROBOTS)


@pytest.mark.parametrize("name", NAMES)
def test_robot_builds_simulates_and_matches_urdf_kinematics(name, tmp_path):
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(robot, tmp_path, urdf, robot_data.package_root())
    # The build's own check must pass: actuators on every joint, no robot bodies touching at
    # home, a floating base on the floor, the hold and the Menagerie test (it raises if not).
    result = mjcfbuild.build(manifest, jobs=2)
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"] and check["actuation"]["problems"] == []
    assert check["resting_contacts"]["pairs"] == []
    assert check["home"] and check["menagerie_test"]["warnings"] == []
    assert set(check["max_joint_speed"]) == {"joint", "speed", "limit"}  # for docs/robots.md
    if robot.floating:
        assert abs(check["floor_gap"]) <= 1e-3
    # solo12's URDF gives every joint 1000 N m, 125-255 times what holds the robot up.
    placeholders = any("effort limits look like placeholders" in w for w in result.warnings)
    assert placeholders == (name == "solo12"), result.warnings
    if robot.floating and not check.get("needs_controller"):
        # The check's stand test passed: 5 s holding home, upright, at height.
        assert check["stand"]["max_tilt"] <= 0.2, check["stand"]
    if name in ("go1", "go2", "a1", "solo12", "anymal_c", "talos"):
        # Their zero pose does not stand; the SRDF the wheel ships beside them has a
        # standing group_state (talos: half_sitting), which the build finds.
        readiness = json.loads((tmp_path / "mjcf/.mjcfbuild/assembly.json").read_text())
        sources = {h["source"] for h in readiness["readiness"]["home"]}
        assert "srdf" in sources, sources

    model = mujoco.MjModel.from_xml_path(str(result.scene))
    data = mujoco.MjData(model)
    for _ in range(2000):
        mujoco.mj_step(model, data)
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))

    urdf_robot = parse_urdf(urdf.read_bytes(), str(urdf))
    kinematics = compare_kinematics(urdf_robot, mujoco.MjModel.from_xml_path(str(result.robot)))
    assert kinematics.missing_links == [] and kinematics.missing_joints == []
    assert kinematics.max_position <= 1e-6, kinematics.worst
    assert kinematics.max_rotation <= 1e-6, kinematics.worst
