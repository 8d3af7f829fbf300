"""Every example builds, loads in MuJoCo and simulates; the arm's meshes are what its script makes."""

from __future__ import annotations

import importlib.util

import mujoco
import numpy as np
import pytest

import mjcfbuild
from tests.conftest import EXAMPLES, copy_example

NAMES = sorted(p.parent.name for p in EXAMPLES.glob("*/robot.yaml"))


@pytest.mark.parametrize("name", NAMES)
def test_example_builds_loads_and_simulates(name, tmp_path):
    folder = copy_example(name, tmp_path)
    result = mjcfbuild.build(folder / "robot.yaml", jobs=2)
    assert result.ok
    model = mujoco.MjModel.from_xml_path(str(result.scene))
    data = mujoco.MjData(model)
    for _ in range(2000):
        mujoco.mj_step(model, data)
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qacc))


def test_arm_meshes_are_exactly_what_the_script_generates():
    spec = importlib.util.spec_from_file_location(
        "make_meshes", EXAMPLES / "arm" / "make_meshes.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for name, data in module.meshes().items():
        assert (EXAMPLES / "arm" / "meshes" / name).read_bytes() == data, name


def test_arm_example_covers_the_formats_it_promises():
    suffixes = {p.suffix for p in (EXAMPLES / "arm" / "meshes").iterdir()}
    assert {".stl", ".dae", ".obj"} <= suffixes


def test_gripper_meshes_are_exactly_what_the_script_generates():
    folder = EXAMPLES / "arm_gripper" / "gripper"
    spec = importlib.util.spec_from_file_location("make_gripper_meshes", folder / "make_meshes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for name, data in module.meshes().items():
        assert (folder / "meshes" / name).read_bytes() == data, name


def test_mjcf_hand_meshes_are_exactly_what_the_script_generates():
    folder = EXAMPLES / "arm_mjcf_gripper" / "hand"
    spec = importlib.util.spec_from_file_location("make_hand_meshes", folder / "make_meshes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for name, data in module.meshes().items():
        assert (folder / "assets" / name).read_bytes() == data, name


def test_quadruped_meshes_are_exactly_what_the_script_generates():
    folder = EXAMPLES / "quadruped"
    spec = importlib.util.spec_from_file_location(
        "make_quadruped_meshes", folder / "make_meshes.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for name, data in module.meshes().items():
        assert (folder / "meshes" / name).read_bytes() == data, name


def test_the_example_quadruped_stands_from_its_bare_manifest(tmp_path):
    """No home, no actuator settings: the check's stand test passes (it fails the build
    otherwise), and the model stands 5 s in MuJoCo when reset to home."""
    folder = copy_example("quadruped", tmp_path)
    result = mjcfbuild.build(folder / "robot.yaml", jobs=2)
    model = mujoco.MjModel.from_xml_path(str(result.scene))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    height = data.qpos[2]
    for _ in range(round(5.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    assert data.qpos[2] > 0.9 * height
    assert data.xmat[1].reshape(3, 3)[2, 2] > 0.98  # upright
