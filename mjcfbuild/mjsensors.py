"""Simulating without computing the model's sensors.

The build's own simulations (the assembly's stand trials, the check, the tuning report) read
no sensor, and MuJoCo computes every sensor at each step: a lidar the build unrolled into
rangefinders casts all its rays each step (TIAGo Pro's two lidars are 1,639 rays, 9 ms a
step; its check took 53 s, 1.1 s without them). Turning sensors off changes none of the
dynamics, so no result of those simulations.
"""

from __future__ import annotations

from typing import Any


def without_sensors(model: Any) -> Any:
    """``model`` (an ``MjModel``) with its sensors off, for a simulation that reads none."""
    import mujoco

    model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_SENSOR)
    return model
