"""Does the model run in MuJoCo Warp? Load it, step several worlds, and look for NaN.

MuJoCo Warp (``pip install mujoco-warp``) is what GPU training pipelines use; ``put_model``
refuses the MuJoCo features it does not support, so loading is itself a compatibility check.
Here it runs on the CPU; the first call compiles Warp's kernels (about a minute), later calls
load them from Warp's kernel cache.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from mjcfbuild.errors import CheckError, UsageError


@dataclass(frozen=True)
class WarpResult:
    """How the model fared in MuJoCo Warp."""

    worlds: int
    steps: int
    finite: bool


def load_warp() -> tuple[Any, Any]:
    """MuJoCo Warp and Warp (``mjw``, ``wp``), quiet: without ``quiet`` Warp prints a banner
    and a line per kernel module it loads (about 40 for one model) into the check's report."""
    try:
        import mujoco_warp as mjw
        import warp as wp
    except ImportError:
        raise UsageError(
            "MuJoCo Warp is not installed", hint="pip install 'mjcfbuild[warp]'"
        ) from None
    # warp-lang 1.19 replaced ``config.quiet`` with ``config.log_level``; set what it reads.
    if hasattr(wp, "LOG_WARNING"):
        wp.config.log_level = wp.LOG_WARNING
    else:  # older warp-lang
        wp.config.quiet = True  # type: ignore[attr-defined]
    return mjw, wp


def check_in_warp(model_path: str, worlds: int = 4, steps: int = 50) -> WarpResult:
    """Load ``model_path`` in MuJoCo Warp and step ``worlds`` copies of it from home."""
    mjw, wp = load_warp()
    import mujoco
    import numpy as np

    model = mujoco.MjModel.from_xml_path(model_path)
    data = mujoco.MjData(model)
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if home >= 0:
        mujoco.mj_resetDataKeyframe(model, data, home)
    mujoco.mj_forward(model, data)
    with wp.ScopedDevice("cpu"):
        try:
            warp_model = mjw.put_model(model)
        except Exception as exc:  # Warp names the unsupported feature
            raise CheckError(
                f"MuJoCo Warp refuses the model: {str(exc).strip().splitlines()[0]}",
                file=model_path,
            ) from None
        warp_data = mjw.put_data(model, data, nworld=worlds)
        for _ in range(steps):
            mjw.step(warp_model, warp_data)
        qpos = warp_data.qpos.numpy()
    finite = bool(np.all(np.isfinite(qpos)))
    if not finite:
        raise CheckError(
            f"MuJoCo Warp: the state is not finite after {steps} steps of {worlds} worlds",
            file=model_path,
        )
    return WarpResult(worlds, steps, finite)
