"""MuJoCo's mesh cache in a worker that served an earlier build: kept for the build's own
products, forgotten before files the user edits are compiled."""

from __future__ import annotations

import time

from tests.engine.test_resident import _box_model


def test_a_later_build_keeps_the_meshes_and_forgets_only_before_user_files(tmp_path):
    import mujoco

    from mjcfbuild import mjcache
    from mjcfbuild.engine.worker_main import _Between, _keep_or_forget_meshes

    mujoco.MjModel.from_xml_path(str(_box_model(tmp_path, 0.5)))
    cache = mujoco.mj_getCache()
    assert mujoco.mj_getCacheSize(cache) > 0
    between = _Between()
    between.holds = "model"
    between.last_end = time.time() - 2.0  # ended in an earlier second
    _keep_or_forget_meshes(between)
    assert between.holds == "model" and mujoco.mj_getCacheSize(cache) > 0
    mjcache.forget_earlier_builds()  # before a composed part, which the user edits
    assert mujoco.mj_getCacheSize(cache) == 0
    mujoco.MjModel.from_xml_path(str(tmp_path / "box.xml"))
    mjcache.forget_earlier_builds()  # once per build: what this build read stays
    assert mujoco.mj_getCacheSize(cache) > 0
