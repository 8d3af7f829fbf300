"""The training variant in MJX, MuJoCo's JAX engine: it loads and the robot stands (slow: JAX
compiles the step on first use)."""

from __future__ import annotations

import pytest

from tests.conftest import copy_example, run_cli

pytestmark = pytest.mark.slow


def test_the_quadruped_variant_loads_and_stands_in_mjx(tmp_path):
    import jax
    import jax.numpy as jnp
    import mujoco
    from mujoco import mjx

    folder = copy_example("quadruped", tmp_path)
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  training: true\n")
    assert run_cli("build", "--no-check", str(manifest)).code == 0
    # Nothing MuJoCo 3.x (MJX's own release) refuses: no input= on the position servos.
    assert "input=" not in (folder / "mjcf" / "example_quadruped_mjx.xml").read_text()
    model = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "scene_mjx.xml"))
    device_model = mjx.put_model(model)  # refuses what MJX does not run (<dcmotor>, for one)
    home = model.key("home")
    data = mjx.make_data(device_model).replace(
        qpos=jnp.asarray(home.qpos), ctrl=jnp.asarray(home.ctrl)
    )
    step = jax.jit(mjx.step)
    for _ in range(round(1.0 / model.opt.timestep)):  # 1 s
        data = step(device_model, data)
    assert bool(jnp.isfinite(data.qpos).all())
    # Standing: the base still near its home height, not fallen or sunk.
    assert abs(float(data.qpos[2]) - home.qpos[2]) < 0.1 * home.qpos[2]
