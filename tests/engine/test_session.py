"""A build sends the steps that compile the model to workers holding it, and warms a second
worker with the model's mesh products while it is assembled."""

from __future__ import annotations

import threading
from pathlib import Path

import mjcfbuild
from mjcfbuild.engine.workers import WorkerPool
from tests.conftest import copy_example


def test_model_steps_carry_the_model_and_a_second_worker_is_warmed(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    asked: list[tuple[str, str | None]] = []
    warmed: list[tuple[str, str, dict]] = []
    lock = threading.Lock()
    run, warm_for = WorkerPool.run, WorkerPool.warm_for

    payloads: dict[str, dict] = {}

    holders: list[bool] = []

    def recording_run(self, step, payload, label, log, timeout, affinity=None, started=None):
        with lock:
            asked.append((label, affinity))
            payloads[label] = payload
        return run(self, step, payload, label, log, timeout, affinity, started)

    def recording_warm_for(
        self, affinity, step, payload, timeout, prepares=(), holders_too=False, until_idle=False
    ):
        with lock:
            warmed.append((affinity, step, payload))
            holders.append(holders_too)
        return warm_for(self, affinity, step, payload, timeout, prepares, holders_too, until_idle)

    monkeypatch.setattr(WorkerPool, "run", recording_run)
    monkeypatch.setattr(WorkerPool, "warm_for", recording_warm_for)
    folder = copy_example("arm", tmp_path)
    result = mjcfbuild.build(folder / "robot.yaml", jobs=2)
    assert result.ok
    model = str(result.robot)
    affinities = dict(asked)
    assert {label for label, affinity in asked if affinity == model} == {
        "selfcollision",
        "assemble",
        "check",
        "previews",
        "tuning",
    }
    assert all(affinities[label] is None for label in affinities if label.startswith("mesh:"))
    # A first build prepares the second worker for the assembly while the matrix is computed
    # (its modules and every mesh product, drawn ones too), then for the check and previews.
    [for_assembly, for_check] = warmed
    for affinity, step, payload in warmed:
        assert (affinity, step) == (model, "mjcfbuild.steps.warm:run")
        assert payload["folders"] and all(Path(f).is_dir() for f in payload["folders"])
    assert for_assembly[2]["modules"] == ["mujoco", "mjcfbuild.steps.assemble"]
    assert for_check[2]["modules"] == []
    # the check's may take the matrix's worker: it holds the model, collision meshes only
    assert holders == [False, True]
    # (the products converted by then, every one the matrix reads among them: a drawn mesh
    # may still be converting beside the matrix)
    products = set(for_assembly[2]["folders"])
    assert set(payloads["selfcollision"]["product_dirs"].values()) <= products
    assert products <= set(for_check[2]["folders"])

    # Without the check there is nothing to warm a second worker for.
    warmed.clear()
    asked.clear()
    xacro = folder / "urdf" / "arm.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('damping="0.5"', 'damping="0.6"', 1))
    assert mjcfbuild.build(folder / "robot.yaml", jobs=2, check=False).ok
    assert ("assemble", model) in asked
    assert warmed == []


def test_a_first_build_starts_its_workers_when_a_step_needs_one_and_a_rebuild_ahead(
    tmp_path, monkeypatch
):
    """Workers started ahead of a first build only took CPU from its mesh steps (measured:
    bench/edit_times.py --bare); a rebuild starts two ahead, importing what it will run."""
    from mjcfbuild.engine.workers import MESH_MODULES, MODEL_MODULES

    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    warmed: list[tuple[str, ...]] = []
    warm = WorkerPool.warm

    def recording_warm(self, preload, *args, **kwargs):
        warmed.append(tuple(preload))
        return warm(self, preload, *args, **kwargs)

    monkeypatch.setattr(WorkerPool, "warm", recording_warm)
    folder = copy_example("arm", tmp_path)
    assert mjcfbuild.build(folder / "robot.yaml", jobs=2).ok
    assert warmed == []

    warmed.clear()
    xacro = folder / "urdf" / "arm.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('damping="0.5"', 'damping="0.6"', 1))
    assert mjcfbuild.build(folder / "robot.yaml", jobs=2).ok
    preloads = [set(preload) for preload in warmed]
    assert any(set(MODEL_MODULES) <= p for p in preloads)
    assert any(set(MESH_MODULES) <= p for p in preloads)
