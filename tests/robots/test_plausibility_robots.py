"""The mesh plausibility test and the COLLADA up-axis decision on real robots: iCub, whose
COLLADA files are tagged Y-up and partly hold Y-up data, has those turned, and Menagerie's
hand-tuned models pass. That every robot of example-robot-data passes is tested on the build
tests/robots/test_real_robots.py makes of it (one build of each robot for both).

The survey of all ~69 URDFs of the wheel is ``bench/plausibility_survey.py``."""

from __future__ import annotations

from pathlib import Path

import pytest

import mjcfbuild
from bench import robot_data
from mjcfbuild.check.loading import asset_sources, compile_model
from mjcfbuild.check.plausibility import check_plausibility

pytestmark = [pytest.mark.robots, pytest.mark.slow]

ICUB = robot_data.Robot("icub", "robots/icub_description/robots/icub.urdf", True)


def built(robot: robot_data.Robot, folder, extra: str = ""):
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(robot, folder, urdf, robot_data.package_root(), extra)
    result = mjcfbuild.build(manifest, jobs=2, check=False)
    sources = asset_sources(folder / "mjcf" / ".mjcfbuild" / "assembly.json")
    return check_plausibility(compile_model(result.robot, sources), sources)


def test_icub_y_up_files_are_turned_and_ignoring_the_tag_is_named(tmp_path):
    found = built(ICUB, tmp_path / "auto")
    assert not [f for f in found.findings if f.cause == "up axis"]
    ignored = built(ICUB, tmp_path / "ignore", "meshes:\n  collada_up_axis: ignore\n")
    up_axis = {f.body for f in ignored.findings if f.cause == "up axis"}
    assert {"l_upper_leg", "r_upper_leg"} <= up_axis


@pytest.mark.parametrize("name", ["go1", "g1"])
def test_hand_tuned_menagerie_models_pass(name, tmp_path):
    """mjlab's asset zoo ships MuJoCo Menagerie's Unitree go1 and g1, hand-tuned (PyPI's only
    copy of Menagerie models; Menagerie's own package fetches them at run time)."""
    import mujoco

    from bench.sim_speed import HAND_TUNED, hand_tuned_model

    scene = hand_tuned_model(name, tmp_path)
    model = mujoco.MjModel.from_xml_path(str(scene.parent / Path(HAND_TUNED[name]).name))
    found = check_plausibility(model)
    assert found.bodies >= 12
    assert found.findings == []
