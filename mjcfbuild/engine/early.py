"""Workers started with the command, before the manifest is read.

A folder's first build starts workers that import the mesh step's modules, two of them then
MuJoCo and a model step's (:func:`first_build_workers`); a rebuild starts the workers it will
need, as follows.

Reading and validating the manifest and importing the engine take a rebuild 0.3-0.5 s, during
which one of the machine's cores is idle. When the no-op path finds that something changed,
the last successful build's stamp still says where that build kept its state and whether it
checked: that is enough to start the workers of a rebuild at once (the same two a rebuild
starts, :func:`~mjcfbuild.engine.workers.rebuild_preloads`), each importing its modules and
then having MuJoCo process the mesh products the previous model used. Most rebuilds use most
of those products unchanged (a joint edit, all of them), and the build finds them processed.
When a mesh file changed, the worker that runs mesh steps only imports: its first step is due.

The stamp is only a prediction: the build adopts the workers only if they suit it
(:meth:`~mjcfbuild.engine.session.BuildSession.adopt`), and a product that changed after a
worker processed it is processed again (mjcfbuild.engine.worker_main), so a wrong prediction
costs time, never correctness.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mjcfbuild.engine.workers import WorkerPool


def start_workers(manifest: str | os.PathLike, run_check: bool, jobs: int) -> WorkerPool | None:
    """The workers of a build of ``manifest`` with ``jobs`` jobs, started now: a rebuild's,
    or where no earlier build of it left a stamp whose state folder still exists, a first
    build's (:func:`first_build_workers`)."""
    from mjcfbuild.engine import stamp

    hint = stamp.previous_build(manifest, run_check) or {}
    logs, report = hint.get("logs"), hint.get("assembly_report")
    if not isinstance(logs, str) or not isinstance(report, str) or not os.path.isdir(logs):
        return first_build_workers(manifest, jobs)
    from mjcfbuild.engine.workers import WorkerPool, rebuild_preloads
    from mjcfbuild.fsutil import normalise

    pool = WorkerPool(jobs, normalise(manifest).parent, Path(logs))
    first, second = rebuild_preloads(bool(hint.get("checks")))
    # The second worker runs the mesh steps: when a mesh changed, its first step comes soon
    # and would wait for whichever mesh the worker is processing.
    second_meshes = None if hint["meshes_moved"] else Path(report)
    pool.warm_in_background((first, 1, Path(report)), (second, 2, second_meshes))
    return pool


def first_build_workers(manifest: str | os.PathLike, jobs: int) -> WorkerPool | None:
    """The workers of a folder's first build, started now, each importing the mesh step's
    modules: its first steps convert meshes, and a worker started when the first of them is
    due takes 0.15 s to begin (g1: the model 0.06-0.08 s sooner, the example arm no later).
    The first two then import MuJoCo and the matrix's or the assembly's step
    (:func:`~mjcfbuild.engine.workers.first_build_preloads`; g1's model came 0.08 and 0.18 s
    sooner in the medians of two A/B runs of eight cold builds each way); not the check's or
    the URDF reader's modules, which took the CPU the manifest and the mesh steps needed. The
    build's state folder is not known before its manifest is read, so what these workers
    print outside their steps (each step has a log of its own) goes to ``logs/workers.log``
    in the cache folder. None where that cannot be written: the build starts its workers
    when a step needs one (a read-only cache never fails a build)."""
    from mjcfbuild.cachedir import user_cache_dir
    from mjcfbuild.engine.workers import MESH_MODULES, WorkerPool, first_build_preloads
    from mjcfbuild.fsutil import normalise

    pool = WorkerPool(jobs, normalise(manifest).parent, user_cache_dir() / "logs")
    try:
        pool.log_dir.mkdir(parents=True, exist_ok=True)
        with open(pool.log_dir / "workers.log", "ab"):
            pass
    except OSError:
        pool.close()
        return None
    first, second = first_build_preloads()
    pool.warm_in_background((first, 1, None), (second, 2, None), (MESH_MODULES, None, None))
    return pool
