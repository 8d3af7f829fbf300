"""The training variant in MJX, MuJoCo's JAX engine: it loads and the robot stands (slow: JAX
compiles the step on first use).

JAX runs in a process of its own: once imported, it warns that every later fork of the test
process (each command a test starts) may deadlock, and the tests after this one start many."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.conftest import copy_example, run_cli

pytestmark = pytest.mark.slow

STAND_IN_MJX = """import json, sys
import jax
import jax.numpy as jnp
import mujoco
from mujoco import mjx

model = mujoco.MjModel.from_xml_path(sys.argv[1])
device_model = mjx.put_model(model)  # refuses what MJX does not run (<dcmotor>, for one)
home = model.key("home")
data = mjx.make_data(device_model).replace(qpos=jnp.asarray(home.qpos), ctrl=jnp.asarray(home.ctrl))
step = jax.jit(mjx.step)
for _ in range(round(1.0 / model.opt.timestep)):  # 1 s
    data = step(device_model, data)
finite = bool(jnp.isfinite(data.qpos).all())
print(json.dumps({"finite": finite, "height": float(data.qpos[2]), "home": float(home.qpos[2])}))
"""


def test_the_quadruped_variant_loads_and_stands_in_mjx(tmp_path):
    folder = copy_example("quadruped", tmp_path)
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  training: true\n")
    assert run_cli("build", "--no-check", str(manifest)).code == 0
    # Nothing MuJoCo 3.x (MJX's own release) refuses: no input= on the position servos.
    assert "input=" not in (folder / "mjcf" / "example_quadruped_mjx.xml").read_text()
    run = subprocess.run(
        [sys.executable, "-c", STAND_IN_MJX, str(folder / "mjcf" / "scene_mjx.xml")],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stderr
    stood = json.loads(run.stdout.splitlines()[-1])
    assert stood["finite"]
    # Standing: the base still near its home height, not fallen or sunk.
    assert abs(stood["height"] - stood["home"]) < 0.1 * stood["home"]
