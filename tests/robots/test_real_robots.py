"""The real robots of example-robot-data build with default settings, load, simulate, and
put every URDF link where the URDF does (checked by code independent of MuJoCo's import); each
passes the mesh plausibility test (no failure; warnings only where the description itself is
off), and the URDF the build exports round-trips the original. Each robot is built once, for
all three tests (a module-scoped fixture; no test writes).

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
from mjcfbuild.check.loading import asset_sources, compile_model
from mjcfbuild.check.plausibility import check_plausibility
from mjcfbuild.urdf.parse import parse_urdf
from tests.export.round_trip import EXPORT, assert_round_trip

pytestmark = [pytest.mark.robots, pytest.mark.slow]


NAMES = sorted(robot_data.ROBOTS)

# Bodies the plausibility test names on these robots (warnings), each a defect of the
# description: allegro's palm has its inertial origin at z +0.0475 where its collision box and
# mesh are at -0.0475; ur5's wrists have theirs at the joint, 4-5 cm from the wrist's geometry.
WRISTS = ("wrist_1_link", "wrist_2_link", "wrist_3_link")
KNOWN = {
    "allegro": {"palm_link": "wrong origin"},
    "ur5": dict.fromkeys(WRISTS, "wrong origin"),
}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """``built(name)``: the folder and result of the robot's build with default settings and
    its check, made the first time a test of this module asks for it (in a cache of its own)."""
    builds: dict[str, tuple] = {}
    cache = tmp_path_factory.mktemp("real-robots-cache")

    def build(name: str):
        if name not in builds:
            robot = robot_data.ROBOTS[name]
            folder = tmp_path_factory.mktemp(name)
            urdf = robot_data.unpack(robot)
            manifest = robot_data.manifest(
                robot, folder, urdf, robot_data.package_root(), extra=EXPORT
            )
            with pytest.MonkeyPatch.context() as patch:
                patch.setenv("MJCFBUILD_CACHE_DIR", str(cache))
                # The build's own check must pass: actuators on every joint, no robot bodies
                # touching at home, a floating base on the floor, the hold and the Menagerie
                # test (it raises if not).
                builds[name] = folder, mjcfbuild.build(manifest, jobs=2)
        return builds[name]

    return build


@pytest.mark.parametrize("name", NAMES)
def test_robot_builds_simulates_and_matches_urdf_kinematics(name, built):
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    folder, result = built(name)
    check = json.loads((folder / "mjcf/.mjcfbuild/check.json").read_text())
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
        readiness = json.loads((folder / "mjcf/.mjcfbuild/assembly.json").read_text())
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


@pytest.mark.parametrize("name", NAMES)
def test_example_robots_pass_the_plausibility_test(name, built):
    folder, result = built(name)
    sources = asset_sources(folder / "mjcf" / ".mjcfbuild" / "assembly.json")
    found = check_plausibility(compile_model(result.robot, sources), sources)
    assert found.failures == []
    assert {f.body: f.cause for f in found.findings} == KNOWN.get(name, {})


@pytest.mark.parametrize("name", NAMES)
def test_the_exported_urdf_keeps_link_poses_and_masses(name, built):
    """URDF -> MJCF -> URDF (tests/export/round_trip.py), on the default, fused build."""
    _, result = built(name)
    assert_round_trip(robot_data.unpack(robot_data.ROBOTS[name]), result.robot, fuse_static=True)
