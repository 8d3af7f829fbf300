"""Steps that report on MuJoCo's state in the process that runs them, for testing what workers
do with MuJoCo's cache."""

from __future__ import annotations


def cache_size(payload: dict) -> dict:
    """The bytes in this process's MuJoCo asset cache."""
    import mujoco

    return {"bytes": mujoco.mj_getCacheSize(mujoco.mj_getCache())}


def mesh_vertices(payload: dict) -> dict:
    """The vertex count MuJoCo compiles the mesh file ``payload["file"]`` to."""
    import mujoco

    spec = mujoco.MjSpec()
    spec.add_mesh(name="mesh", file=payload["file"])
    return {"vertices": spec.compile().nmeshvert}
