"""A MuJoCo error while simulating is a check failure naming what ran and what to do, never
an internal error (exit 70) with a traceback.

The quadruped example's contacts outgrow a 10 KB arena: MuJoCo compiles it (the compiler
drops contacts that do not fit with a warning) but raises ``mujoco.FatalError``
(``mj_stackAlloc: out of memory``) at its first step with the feet on the floor.
"""

from __future__ import annotations

import json

import mujoco
import pytest

from mjcfbuild.errors import EXIT_CHECK
from mjcfbuild.mjstopped import SimulationStopped, simulating, stopped_line
from tests.conftest import copy_example, run_cli

TINY_ARENA = "mujoco_inputs:\n  raw: '<size memory=\"10K\"/>'\n"


def test_a_fatal_error_inside_becomes_a_line_naming_what_ran():
    # Two balls dropped on a floor with a 4 KB arena: MuJoCo runs out when they land.
    model = mujoco.MjModel.from_xml_string(
        '<mujoco><size memory="4K"/><worldbody><geom type="plane" size="1 1 .1"/>'
        '<body pos="0 0 0.05"><freejoint/><geom size="0.02"/></body>'
        '<body pos="0.1 0 0.05"><freejoint/><geom size="0.02"/></body>'
        "</worldbody></mujoco>"
    )
    data = mujoco.MjData(model)
    with pytest.raises(SimulationStopped) as stopped, simulating("200 steps of the balls"):
        for _ in range(200):
            mujoco.mj_step(model, data)
    line = stopped.value.line
    assert line.startswith("MuJoCo stopped 200 steps of the balls: mj_stackAlloc: out of memory")
    assert '<size memory="..."/>' in line and "\n" not in line


def test_other_errors_pass_through():
    with pytest.raises(KeyError), simulating("nothing"):
        raise KeyError("not MuJoCo's")


def test_an_error_that_is_not_about_memory_says_to_look_in_the_viewer():
    line = stopped_line("the trial", "mj_somethingElse: bad\nmore detail")
    assert line == (
        "MuJoCo stopped the trial: mj_somethingElse: bad "
        "(simulate the model in MuJoCo's viewer to see where it goes wrong)"
    )


@pytest.mark.slow
def test_the_checks_simulation_running_out_of_memory_fails_the_check(tmp_path):
    folder = copy_example("quadruped", tmp_path)
    manifest = folder / "robot.yaml"
    # A home of the manifest's: the build's own stand trial is not needed, the check runs.
    manifest.write_text(manifest.read_text() + TINY_ARENA + "home:\n  front_left_hip_joint: 0\n")
    result = run_cli("build", str(manifest))
    assert result.code == EXIT_CHECK, result.stderr
    errors = [line for line in result.stderr.splitlines() if "error" in line]
    assert len(errors) == 1 and "Traceback" not in result.stderr
    assert (
        "check: MuJoCo stopped 2000 zero-control steps of scene.xml: mj_stackAlloc" in (errors[0])
    )
    record = json.loads((folder / "mjcf/.mjcfbuild/check.json").read_text())
    assert record["simulation"]["stopped"] and not record["passes"]
    # Each simulation of the control checks says it stopped; the other checks still ran.
    assert any("the Menagerie test" in failure for failure in record["failures"])
    assert record["kinematics"]["max_position_error"] < 1e-6


@pytest.mark.slow
def test_the_builds_stand_trial_running_out_of_memory_fails_with_the_checks_code(tmp_path):
    folder = copy_example("quadruped", tmp_path)
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text() + TINY_ARENA)
    result = run_cli("build", str(manifest))
    assert result.code == EXIT_CHECK, result.stderr
    assert "Traceback" not in result.stderr
    (error,) = [line for line in result.stderr.splitlines() if "error" in line]
    assert error.startswith(f"mjcfbuild: error: {manifest}: MuJoCo stopped the build's 3 s trial")
    assert "whether the robot stands at home: mj_stackAlloc: out of memory" in error
