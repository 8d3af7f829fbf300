"""A built model simulates: finite state and no MuJoCo warning over 2,000 zero-control steps."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class SimulationResult:
    """What happened over the steps."""

    steps: int
    finite: bool
    warnings: list[str] = field(default_factory=list)

    @property
    def passes(self) -> bool:
        """Finite and quiet."""
        return self.finite and not self.warnings


def simulate(model, steps: int = 2000) -> SimulationResult:
    """Step ``model`` from its initial state with zero control."""
    import mujoco
    import numpy as np

    data = mujoco.MjData(model)
    finite = True
    for _ in range(steps):
        mujoco.mj_step(model, data)
        if not (np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))):
            finite = False
            break
    warnings = [
        f"{mujoco.mjtWarning(index).name.removeprefix('mjWARN_').lower()} "
        f"(x{int(stat.number)}, last info {int(stat.lastinfo)})"
        for index, stat in enumerate(data.warning)
        if stat.number
    ]
    return SimulationResult(steps, finite, warnings)
