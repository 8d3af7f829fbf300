"""MuJoCo's mesh cache in a worker that served an earlier build (a resident worker).

MuJoCo keeps processed meshes across compiles, telling files apart by name and modification
time in whole seconds. The files the build writes are safe to keep across builds
(mjcfbuild.engine.worker_main empties the cache when a build follows within a second); files
the user edits, such as the meshes of a composed MJCF part, could have been changed twice in
the second the last build compiled them. Steps that compile such files call
:func:`forget_earlier_builds` first.
"""

from __future__ import annotations

_kept = False


def kept_from_earlier_build() -> None:
    """Note that MuJoCo's cache may hold files an earlier build compiled."""
    global _kept
    _kept = True


def forget_earlier_builds() -> None:
    """Empty MuJoCo's cache if it may hold files an earlier build compiled."""
    global _kept
    if _kept:
        import mujoco

        mujoco.mj_clearCache(mujoco.mj_getCache())
        _kept = False
