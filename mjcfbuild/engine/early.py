"""Workers started with the command, before the manifest is read.

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
    """The workers of a rebuild of ``manifest`` with ``jobs`` jobs, started now, or None when
    no earlier build of it left a stamp whose state folder still exists."""
    from mjcfbuild.engine import stamp

    hint = stamp.previous_build(manifest, run_check) or {}
    logs, report = hint.get("logs"), hint.get("assembly_report")
    if not isinstance(logs, str) or not isinstance(report, str):
        return None
    if not os.path.isdir(logs):
        return None  # moved or cleaned: the build starts its own workers where they belong
    from mjcfbuild.engine.workers import WorkerPool, rebuild_preloads
    from mjcfbuild.fsutil import normalise

    pool = WorkerPool(jobs, normalise(manifest).parent, Path(logs))
    first, second = rebuild_preloads(bool(hint.get("checks")))
    pool.warm(first, count=1, meshes_from=Path(report))
    # The second worker runs the mesh steps: when a mesh changed, its first step comes soon
    # and would wait for whichever mesh the worker is processing.
    pool.warm(second, count=2, meshes_from=None if hint["meshes_moved"] else Path(report))
    return pool
