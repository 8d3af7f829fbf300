"""Unitree's go1 from example-robot-data with the catalogue's go1 drives: the rotor's armature,
the peak torques and the torque-speed lines in the model, standing on bent knees, and every
joint within its drive's speed under the model test."""

from __future__ import annotations

import json

import mujoco
import pytest

import mjcfbuild
from bench import robot_data

pytestmark = [pytest.mark.robots, pytest.mark.slow]

DRIVES = """actuators:
  rules:
    - {joints: ["*_calf_joint"], motor: go1_knee}
    - {joints: ["*_hip_joint", "*_thigh_joint"], motor: go1_hip}
home: {"*_thigh_joint": 0.9, "*_calf_joint": -1.8}
"""


def test_go1_with_its_drives(tmp_path):
    robot = robot_data.ROBOTS["go1"]
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(robot, tmp_path, urdf, robot_data.package_root(), DRIVES)
    result = mjcfbuild.build(manifest, jobs=2)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    for leg in ("FL", "FR", "RL", "RR"):
        for joint, ratio, peak in (("calf", 9, 35.55), ("thigh", 6, 23.7), ("hip", 6, 23.7)):
            index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, f"{leg}_{joint}_joint")
            assert model.dof_armature[model.jnt_dofadr[index]] == pytest.approx(
                0.000111842 * ratio**2, abs=1e-9
            )
            (actuator,) = [a for a in range(model.nu) if model.actuator_trnid[a, 0] == index]
            assert model.actuator_forcerange[actuator][1] == pytest.approx(peak)
            assert model.actuator_gaintype[actuator] == mujoco.mjtGain.mjGAIN_DCMOTOR
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"], check["failures"]
    assert check["hold"]["base_tilt"] < 0.3  # it stands
    fastest = check["max_joint_speed"]
    assert fastest["speed"] <= 1.5 * fastest["limit"], fastest
    tuning = json.loads((tmp_path / "mjcf/.mjcfbuild/tuning.json").read_text())
    assert [g["label"] for g in tuning["groups"]] == [
        "actuators.rules[0]: *_calf_joint",
        "actuators.rules[1]: *_hip_joint, *_thigh_joint",
    ]


def test_tiagos_hand_is_three_underactuated_mechanisms_and_its_wrist_none():
    # The real description: the Hey5 hand's transmissions name one motor for each finger
    # group (PAL's own Hey5Reducer type), commanding one joint and reading the others; the
    # wrist is a differential of two motors.
    from lxml import etree

    from mjcfbuild.control.motors import reductions, underactuated
    from mjcfbuild.inputs.ros2_control import read_ros2_control

    urdf = robot_data.unpack(robot_data.ROBOTS["tiago"])
    control = read_ros2_control(etree.parse(str(urdf)).getroot(), "tiago.urdf")
    joints = {t.joint for t in control.transmissions}
    found = underactuated(control.transmissions, joints)
    assert [(len(m), m[0].joint, m[0].actuators) for m in found] == [
        (6, "hand_thumb_joint", ["hand_thumb_motor"]),
        (8, "hand_index_joint", ["hand_index_motor"]),
        (22, "hand_mrl_joint", ["hand_mrl_motor"]),
    ]
    assert all(m[0].commands() and not any(t.commands() for t in m[1:]) for m in found)
    geared = reductions(control.transmissions, found)
    assert not {t.joint for m in found for t in m[1:]} & set(geared)
