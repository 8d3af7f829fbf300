"""The reference converter's demo converts, in all three forms, to a model equivalent to the
reference converter's own output, the lidar's 24 rays included (mujoco_ros2_control's count)."""

from __future__ import annotations

import shutil
from pathlib import Path

import mujoco
import numpy as np
import pytest

import mjcfbuild
from mjcfbuild.check.kinematics import compare_kinematics
from mjcfbuild.inputs.frames import ray_direction
from mjcfbuild.sources.expand import expand_xacro
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.parse import parse_urdf
from tests.conftest import EXAMPLES, ROOT, run_cli
from tests.reference_fixtures import MARKER, RELATIVE, find_reference_demo

FIXTURES = find_reference_demo(ROOT, Path.cwd())
REFERENCE = FIXTURES / MARKER if FIXTURES else None
DEMO = EXAMPLES / "reference_demo"


def names(model, kind, count):
    return sorted(mujoco.mj_id2name(model, kind, i) for i in range(count))


@pytest.fixture(scope="module")
def reference():
    if REFERENCE is None:
        pytest.skip(
            f"the reference converter's output ({RELATIVE / MARKER}) is not in any folder above "
            f"{ROOT}; set MJCFBUILD_REFERENCE_DEMO to its reference_demo folder"
        )
    return mujoco.MjModel.from_xml_path(str(REFERENCE))


@pytest.fixture(scope="module")
def urdf_robot():
    expansion = expand_xacro(
        DEMO / "test_robot.urdf",
        {"use_pid": "true", "use_mjcf_from_topic": "true"},
        PackageResolver({"mujoco_ros2_control_demos": DEMO}, {}),
    )
    return parse_urdf(expansion.urdf)


@pytest.fixture(scope="module", params=["embedded", "inputs file", "robot.yaml"])
def built(request, tmp_path_factory):
    folder = tmp_path_factory.mktemp(request.param.replace(" ", "_"))
    if request.param == "embedded":
        shutil.copytree(DEMO, folder / "demo", ignore=shutil.ignore_patterns("mjcf"))
        result = mjcfbuild.build(folder / "demo" / "robot.yaml", jobs=1)
        return mujoco.MjModel.from_xml_path(str(result.scene))
    if request.param == "inputs file":
        run = run_cli(
            "convert",
            "-u",
            str(DEMO / "test_robot.urdf"),
            "-m",
            str(DEMO / "test_inputs.xml"),
            "-o",
            "out",
            "-s",
            "--package",
            f"mujoco_ros2_control_demos={DEMO}",
            "-j",
            "1",
            cwd=folder,
        )
        assert run.code == 0, run.stderr
        return mujoco.MjModel.from_xml_path(str(folder / "out" / "scene.xml"))
    shutil.copytree(
        EXAMPLES / "reference_demo_native", folder / "native", ignore=shutil.ignore_patterns("mjcf")
    )
    shutil.copytree(DEMO, folder / "reference_demo", ignore=shutil.ignore_patterns("mjcf"))
    result = mjcfbuild.build(folder / "native" / "robot.yaml", jobs=1)
    return mujoco.MjModel.from_xml_path(str(result.scene))


def test_joints_and_ranges(built, reference):
    for model in (built, reference):
        assert names(model, mujoco.mjtObj.mjOBJ_JOINT, model.njnt) == [
            "gripper_left_finger_joint",
            "gripper_right_finger_joint",
            "joint1",
            "joint2",
        ]
    for name in ("joint1", "joint2", "gripper_left_finger_joint", "gripper_right_finger_joint"):
        ours = built.jnt_range[mujoco.mj_name2id(built, mujoco.mjtObj.mjOBJ_JOINT, name)]
        theirs = reference.jnt_range[mujoco.mj_name2id(reference, mujoco.mjtObj.mjOBJ_JOINT, name)]
        assert np.allclose(ours, theirs)


def test_actuators_tendon_equality_option(built, reference):
    assert names(built, mujoco.mjtObj.mjOBJ_ACTUATOR, built.nu) == names(
        reference, mujoco.mjtObj.mjOBJ_ACTUATOR, reference.nu
    )
    for name in ("joint1", "joint2", "gripper_left_finger_joint"):
        a = mujoco.mj_name2id(built, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        b = mujoco.mj_name2id(reference, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        assert np.allclose(built.actuator_gainprm[a][:3], reference.actuator_gainprm[b][:3])
        assert np.allclose(built.actuator_ctrlrange[a], reference.actuator_ctrlrange[b])
        assert built.actuator_trntype[a] == reference.actuator_trntype[b]
    assert names(built, mujoco.mjtObj.mjOBJ_TENDON, built.ntendon) == ["split"]
    assert np.allclose(sorted(built.wrap_prm[: built.nwrap]), [-0.5, 0.5])
    # The inputs' equality (the reference keeps a second, duplicate one from the <mimic>).
    assert built.neq == 1
    equality = built.eq_data[0][:5]
    assert np.allclose(equality, [0, -1, 0, 0, 0])
    assert (
        built.opt.integrator == reference.opt.integrator == mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    )


def test_sensors_have_the_reference_names(built, reference):
    # The lidar's -0.3 to 0.3 by 0.025 is 24 rays to the reference converter and to the
    # runtime, which both count int(0.6 / 0.025) + 1 and 0.6 / 0.025 is 23.999999999999996.
    ours = names(built, mujoco.mjtObj.mjOBJ_SENSOR, built.nsensor)
    theirs = names(reference, mujoco.mjtObj.mjOBJ_SENSOR, reference.nsensor)
    assert ours == theirs
    assert [n for n in ours if n.startswith("lidar")] == [f"lidar-{i:02d}" for i in range(24)]


def test_modified_attributes(built):
    joint = mujoco.mj_name2id(built, mujoco.mjtObj.mjOBJ_JOINT, "joint1")
    dof = built.jnt_dofadr[joint]
    assert built.dof_damping[dof] == 2.0 and built.dof_frictionloss[dof] == 1.0
    assert built.body_gravcomp[mujoco.mj_name2id(built, mujoco.mjtObj.mjOBJ_BODY, "forearm")] == 1.0


def test_camera_at_the_reference_world_pose(built, reference):
    for qpos in ([0, 0, 0, 0], [0.4, -0.7, 0.01, -0.01]):
        poses = []
        for model in (built, reference):
            data = mujoco.MjData(model)
            for name, value in zip(
                ("joint1", "joint2", "gripper_left_finger_joint", "gripper_right_finger_joint"),
                qpos,
                strict=True,
            ):
                data.qpos[
                    model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)]
                ] = value
            mujoco.mj_kinematics(model, data)
            mujoco.mj_camlight(model, data)  # camera poses are not part of mj_kinematics
            camera = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "camera")
            assert np.linalg.norm(data.cam_xpos[camera]) > 0.5
            poses.append((data.cam_xpos[camera].copy(), data.cam_xmat[camera].copy()))
        assert np.allclose(poses[0][0], poses[1][0], atol=1e-5)
        assert np.allclose(poses[0][1], poses[1][1], atol=1e-5)  # the reference rounds to 6 digits
        assert built.cam_fovy[0] == 58 and list(built.cam_resolution[0]) == [640, 480]


def test_every_link_at_its_urdf_pose(built, urdf_robot):
    result = compare_kinematics(urdf_robot, built)
    assert result.passes(), result


def test_lidar_has_the_runtimes_24_rays_each_along_its_sweep(built, urdf_robot):
    data = mujoco.MjData(built)
    mujoco.mj_kinematics(built, data)
    frame = link_poses(urdf_robot)["lidar_sensor_frame"]
    for index in range(24):
        site = mujoco.mj_name2id(built, mujoco.mjtObj.mjOBJ_SITE, f"rf-{index:02d}")
        assert site >= 0
        ray = data.site_xmat[site].reshape(3, 3)[:, 2]  # rangefinders measure along +z
        assert np.allclose(ray, ray_direction(frame, -0.3, 0.025, index), atol=1e-9)
        assert np.allclose(data.site_xpos[site], frame.position, atol=1e-12)
    assert mujoco.mj_name2id(built, mujoco.mjtObj.mjOBJ_SITE, "rf-24") == -1


def test_the_reference_output_is_found_from_a_clone_at_any_depth(tmp_path, monkeypatch):
    """CI's clean clone is not necessarily a sibling of shared/: the parity tests must not
    quietly skip there."""
    monkeypatch.delenv("MJCFBUILD_REFERENCE_DEMO", raising=False)
    fixtures = tmp_path / RELATIVE
    (fixtures / MARKER).parent.mkdir(parents=True)
    (fixtures / MARKER).write_text("<mujoco/>")
    clone = tmp_path / "ci" / "build" / "mjcfbuild"
    clone.mkdir(parents=True)
    assert find_reference_demo(clone) == fixtures
    elsewhere = tmp_path / "other"
    monkeypatch.setenv("MJCFBUILD_REFERENCE_DEMO", str(fixtures))
    assert find_reference_demo(elsewhere) == fixtures
