"""Step ``tuning``: the tuning report (see mjcfbuild.check.tuning): each actuator group's step
and sine response in the built model, a table in ``tuning.json`` and a plot per group."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from mjcfbuild.check.loading import asset_sources, compile_model, spec_reading_sources
from mjcfbuild.check.tuning import groups_of, measure, stand_spec
from mjcfbuild.check.tuning_plot import plot_group
from mjcfbuild.errors import ModelError
from mjcfbuild.mjstopped import SimulationStopped, simulating
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import TuningPayload


def run(payload: dict) -> dict:
    """Measure every group and write its plot and the record; plots of groups gone are
    removed. A model that does not load writes nothing (the check says why)."""
    import mujoco

    request = TuningPayload.from_dict(payload)
    folder, record = Path(request.folder), Path(request.record)
    try:
        assembly = json.loads(Path(request.assembly_report).read_text())
    except (OSError, ValueError):
        assembly = {}
    readiness = assembly.get("readiness") or {}
    groups = groups_of(readiness.get("actuators", []), request.rules)
    outputs: dict[str, str] = {}
    summaries, plots = [], {}
    if groups:
        sources = asset_sources(Path(request.assembly_report))
        try:
            built = compile_model(Path(request.model), sources)
            spec = (
                spec_reading_sources(Path(request.model), sources)
                if sources
                else mujoco.MjSpec.from_file(request.model)
            )
            stand_spec(spec)
            model = spec.compile()
        except (ModelError, ValueError):
            return {"outputs": {}}
        home_qpos, home_ctrl = _home(built)
        try:
            with simulating("the tuning report's step and sweep of each group"):
                measured = measure(model, home_qpos, home_ctrl, groups)
        except SimulationStopped as stop:
            return {"outputs": {}, "warnings": [f"no tuning report: {stop.line}"]}
        for group in measured:
            if not group.joints:  # none of its actuators is in the model any more
                continue
            summaries.append(group.summary())
            name = f"{group.name}.png"
            write_output(folder / name, plot_group(group), outputs)
            plots[group.name] = f"tuning/{name}"
    if folder.is_dir():
        for stale in folder.glob("*.png"):
            if stale.stem not in plots:
                stale.unlink()
    text = json.dumps({"groups": summaries, "plots": plots}, indent=1, sort_keys=True) + "\n"
    write_output(record, text.encode(), outputs)
    return {"outputs": outputs}


def _home(model: Any) -> tuple[dict[str, float], dict[str, float]]:
    """The home keyframe's hinge and slide positions by joint name and its controls by
    actuator name (the model's initial state where it has no home)."""
    import mujoco

    data = mujoco.MjData(model)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if key >= 0:
        mujoco.mj_resetDataKeyframe(model, data, key)
    kinds = (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)
    qpos = {
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j): float(
            data.qpos[model.jnt_qposadr[j]]
        )
        for j in range(model.njnt)
        if model.jnt_type[j] in kinds
    }
    ctrl = {
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, a): float(data.ctrl[a])
        for a in range(model.nu)
    }
    return qpos, ctrl
