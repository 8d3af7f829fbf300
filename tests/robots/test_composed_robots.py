"""Two real descriptions from example-robot-data composed into one model: a UR5 with an Allegro
hand at its tool flange. The build's check covers both (kinematics of every link, actuators,
the hold), and the hand's links sit where the UR5's tool0 and the hand's own URDF put them."""

from __future__ import annotations

import json

import mujoco
import numpy as np
import pytest

import mjcfbuild
from bench import robot_data
from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.parse import parse_urdf
from mjcfbuild.urdf.transforms import Transform

pytestmark = [pytest.mark.robots, pytest.mark.slow]


def test_ur5_with_an_allegro_hand(tmp_path):
    ur5 = robot_data.unpack(robot_data.ROBOTS["ur5"])
    hand = robot_data.unpack(robot_data.ROBOTS["allegro"])
    manifest = tmp_path / "robot.yaml"
    manifest.write_text(
        "name: ur5_allegro\n"
        f"source: {{urdf: {ur5}}}\n"
        f"packages: {{example-robot-data: {robot_data.package_root()}}}\n"
        "attach:\n"
        f"  - source: {{urdf: {hand}}}\n"
        "    to: tool0\n"
        "    prefix: hand_\n"
        "    pos: [0, 0, 0.01]\n"
        "home: {hand_joint_1.0: 0.3}\n"
    )
    result = mjcfbuild.build(manifest, jobs=2)
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"] and check["actuation"]["problems"] == []
    assert check["kinematics"]["missing_links"] == []

    model = mujoco.MjModel.from_xml_path(str(result.robot))
    hand_robot = parse_urdf(hand.read_bytes(), str(hand))
    hand_joints = [j.name for j in hand_robot.joints if j.moves]
    actuated = {model.actuator(i).name for i in range(model.nu)}
    assert {f"hand_{name}" for name in hand_joints} <= actuated
    assert len(actuated) == 6 + len(hand_joints)
    key = model.key("home")
    assert key.qpos[model.jnt_qposadr[model.joint("hand_joint_1.0").id]] == pytest.approx(0.3)

    # The hand's own forward kinematics, from its own URDF, relative to the attachment frame.
    data = mujoco.MjData(model)
    data.qpos[:] = key.qpos
    mujoco.mj_forward(model, data)
    config = {
        name: float(data.qpos[model.jnt_qposadr[model.joint(f"hand_{name}").id]])
        for name in hand_joints
    }
    tool = model.site("tool0")
    rotation = tuple(tuple(float(v) for v in row) for row in data.site_xmat[tool.id].reshape(3, 3))
    tool_pose = Transform(rotation, tuple(float(v) for v in data.site_xpos[tool.id]))
    attachment = tool_pose.compose(Transform(position=(0.0, 0.0, 0.01)))
    for link, pose in link_poses(hand_robot, config).items():
        site = model.site(f"hand_{link}")
        want = attachment.compose(pose)
        assert np.allclose(data.site_xpos[site.id], want.position, atol=1e-9), link
        got = data.site_xmat[site.id].reshape(3, 3)
        assert np.allclose(got, np.array(want.rotation), atol=1e-9), link
