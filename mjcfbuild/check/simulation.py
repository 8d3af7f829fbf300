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
        f"(x{int(stat.number)}, {_where(model, index, int(stat.lastinfo))})"
        for index, stat in enumerate(data.warning)
        if stat.number
    ]
    return SimulationResult(steps, finite, warnings)


def _where(model, warning: int, info: int) -> str:
    """Where MuJoCo's warning happened: the joint of the DOF it records for an unstable
    velocity or acceleration (a bare index said nothing to a user), else its number. A
    floating base's DOFs come first and move with any runaway, so MuJoCo records them on a
    floating robot whichever joint ran away: they are not named as the culprit."""
    import mujoco

    if warning not in (mujoco.mjtWarning.mjWARN_BADQVEL, mujoco.mjtWarning.mjWARN_BADQACC):
        return f"last info {info}"
    joint = dof_joint(model, info)
    if joint is None:
        return f"last info {info}"
    if int(model.jnt_type[model.dof_jntid[info]]) == int(mujoco.mjtJoint.mjJNT_FREE):
        return f"last at the floating base '{joint}', which any joint's runaway moves"
    return f"last at joint '{joint}'"


def dof_joint(model, dof: int) -> str | None:
    """The name of the joint that DOF ``dof`` belongs to; None for no such DOF or no name."""
    import mujoco

    if not 0 <= dof < model.nv:
        return None
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, model.dof_jntid[dof])
