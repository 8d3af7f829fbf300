"""The training variant proven in MuJoCo Warp on the CPU (slow: Warp loads its kernels for
each model, and compiles them on first use)."""

from __future__ import annotations

import json

import pytest

from mjcfbuild.check.warp_variant import behaviour
from tests.conftest import copy_example, run_cli

pytest.importorskip("mujoco_warp")
pytestmark = pytest.mark.slow


def with_training(tmp_path, example):
    folder = copy_example(example, tmp_path)
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  training:\n    self_contacts: true\n")
    assert run_cli("build", "--no-check", str(manifest)).code == 0
    return folder


def test_check_warp_proves_the_quadruped_variant_against_the_full_model(tmp_path):
    folder = with_training(tmp_path, "quadruped")
    result = run_cli("check", "--warp", str(folder / "robot.yaml"))
    assert result.code == 0, result.stderr
    assert "training variant in MuJoCo Warp (cpu, 64 worlds, 100 steps" in result.stdout
    assert "stands at home for 5 s" in result.stdout
    # Warp's banner and its line per kernel module loaded stay out of the report.
    assert "initialized" not in result.stdout and "load on device" not in result.stdout
    record = json.loads((folder / "mjcf" / ".mjcfbuild" / "training_warp.json").read_text())
    full, variant = record["full"], record["variant"]
    assert variant["finite"] and full["finite"] and record["failures"] == []
    assert variant["contact_pairs"] < full["contact_pairs"]
    assert variant["steps_per_second"] > 0 and full["steps_per_second"] > 0
    # The build report shows the variant and these figures, while they are the variant's.
    report = (folder / "mjcf" / "report" / "report.md").read_text()
    assert "## Training variant" in report and "| variant | 10 |" in report
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text() + "    iterations: 5\n")
    assert run_cli("build", "--no-check", str(manifest)).code == 0
    report = (folder / "mjcf" / "report" / "report.md").read_text()
    assert "Not yet measured in MuJoCo Warp" in report and "| variant |" not in report
    # It names the solver settings the variant has: the GPU's, with the iterations given.
    import mujoco

    option = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "scene_mjx.xml")).opt
    assert (option.solver, option.iterations, option.ls_iterations) == (2, 5, 5)  # Newton
    assert "Solver for a GPU: newton, 5 iterations, 5 line-search iterations" in report


def test_the_arm_variant_holds_home_and_the_hold_can_fail(tmp_path):
    folder = with_training(tmp_path, "arm")
    scene = str(folder / "mjcf" / "scene_mjx.xml")
    line, failure = behaviour(scene, hold_tolerance=0.05)
    assert line.startswith("holds home for 1 s") and failure == ""
    # The same run judged by a tolerance no servo meets: the check does fail.
    _, failure = behaviour(scene, hold_tolerance=1e-9)
    assert failure.startswith("the training variant does not hold home")


@pytest.mark.robots
def test_the_go1_variant_stands_for_5_s_in_warp(tmp_path):
    import mjcfbuild
    from bench import robot_data

    robot = robot_data.ROBOTS["go1"]
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(
        robot, tmp_path, urdf, robot_data.package_root(), "output:\n  training: true\n"
    )
    result = mjcfbuild.build(manifest, check=False)
    line, failure = behaviour(str(result.scene.parent / "scene_mjx.xml"), hold_tolerance=0.05)
    assert line.startswith("stands at home for 5 s") and failure == "", line


BLOCKING_RUNNER = """import runpy, sys
BLOCKED = {"trimesh", "pydantic", "doit", "coacd", "yaml", "scipy", "fsspec", "dask", "lxml"}
class Block:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in BLOCKED:
            raise ImportError("not on the GPU machine: " + name)
sys.meta_path.insert(0, Block())
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name="__main__")
"""


def test_the_bench_measures_an_exported_folder_without_the_build_dependencies(tmp_path):
    import subprocess
    import sys
    from pathlib import Path

    from bench import warp_speed

    folder = with_training(tmp_path, "arm")
    out = folder / "mjcf"
    plan = [
        {
            "robot": "arm",
            "scenes": [
                ["full model", str(out / "scene.xml")],
                ["training variant (gpu)", str(out / "scene_mjx.xml")],
            ],
            "variants": [["gpu", str(out / "scene_mjx.xml")]],
        }
    ]
    exported = tmp_path / "exported"
    archive = warp_speed.export(plan, exported, {"worlds": 4, "steps": 3, "rounds": 1})
    assert sorted(p.name for p in exported.iterdir()) == ["bench.json", archive.name]
    (folder / "mjcf").rename(tmp_path / "gone")  # the export stands on its own
    runner = tmp_path / "runner.py"
    runner.write_text(BLOCKING_RUNNER)
    script = Path(warp_speed.__file__)
    result = subprocess.run(
        [sys.executable, str(runner), str(script), "--from", str(exported), "--device", "cpu"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env={"PATH": "/usr/bin:/bin", "HOME": str(Path.home())},
    )
    assert result.returncode == 0, result.stderr
    assert "MuJoCo Warp on cpu (" in result.stdout and "4 worlds, 3 steps" in result.stdout
    assert "| arm | full model | Newton 100/50 |" in result.stdout
    assert "| arm | training variant (gpu) | Newton 1/5 |" in result.stdout
    assert "- arm variants in Warp: (gpu) holds home for 1 s" in result.stdout


def test_warp_buffers_are_sized_from_what_the_scene_reaches(tmp_path):
    import mujoco

    from mjcfbuild.check.warp_variant import _home, measure, noisy_ctrl, sizes

    folder = with_training(tmp_path, "quadruped")
    scene = str(folder / "mjcf" / "scene.xml")
    model = mujoco.MjModel.from_xml_path(scene)
    data = _home(model)
    ctrl = noisy_ctrl(model, data, 4, 0.1)
    nconmax, njmax = sizes(model, data, ctrl, 20)
    # Each of the worlds, stepped the same way, stays within half of each buffer.
    for row in ctrl:
        rollout = _home(model)
        rollout.ctrl[:] = row
        for _ in range(20):
            mujoco.mj_step(model, rollout)
            assert 2 * rollout.ncon <= nconmax and 2 * rollout.nefc <= njmax
    assert nconmax >= max(8, 2 * data.ncon) and njmax >= max(16, 2 * data.nefc)
    figures = measure(scene, worlds=4, steps=19)
    assert (figures.nconmax, figures.njmax) == (nconmax, njmax) and figures.finite


def test_the_gpu_proof_records_figures_and_turns_a_device_error_into_a_failure(tmp_path):
    """What check --warp does where Warp finds a GPU, run here on the CPU (the same Warp calls
    with another device name), and on a device that does not exist: the error is a failure
    naming the device, never a traceback that loses the CPU's result."""
    from mjcfbuild.check.warp_variant import prove_on_gpu

    folder = with_training(tmp_path, "arm")
    full, variant = (str(folder / "mjcf" / name) for name in ("scene.xml", "scene_mjx.xml"))
    record, failures = prove_on_gpu(full, variant, 0.05, "cpu", "this CPU", worlds=8)
    assert failures == [] and record["device"] == "this CPU"
    assert record["variant"]["worlds"] == 8 and record["variant"]["finite"]
    assert record["behaviour"].startswith("holds home for 1 s")
    record, failures = prove_on_gpu(full, variant, 0.05, "cuda:7", "a missing GPU", worlds=8)
    assert failures == [record["error"]] and failures[0].startswith(
        "MuJoCo Warp failed on a missing GPU: "
    )
