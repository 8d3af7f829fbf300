"""A worker process processes the previous model's meshes while it waits, and never lets
MuJoCo's cache hand a step a mesh that has changed since."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

from mjcfbuild.engine.worker_main import idle_work
from mjcfbuild.engine.workers import WorkerPool
from tests.conftest import ROOT

STEPS = "tests.engine.mujoco_steps"


def _tetrahedron() -> str:
    return "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"


def _cube() -> str:
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    lines = [f"v {x} {y} {z}" for x, y, z in corners]
    for a, b, c, d in faces:
        lines += [f"f {a} {b} {c}", f"f {a} {c} {d}"]
    return "\n".join(lines) + "\n"


def _report(tmp_path: Path) -> tuple[Path, Path]:
    """An assembly report naming one product mesh (a tetrahedron); (report, mesh)."""
    mesh = tmp_path / "state" / "products" / "part" / "mesh.obj"
    mesh.parent.mkdir(parents=True)
    mesh.write_text(_tetrahedron())
    report = tmp_path / "state" / "assembly.json"
    report.write_text(json.dumps({"asset_sources": {"part.obj": "products/part/mesh.obj"}}))
    return report, mesh


def _wait_until_cached(pool: WorkerPool) -> int:
    deadline = time.monotonic() + 60
    while (size := pool.run(f"{STEPS}:cache_size", {}, "size", None, 60)["bytes"]) == 0:
        assert time.monotonic() < deadline, "the worker never processed the mesh"
        time.sleep(0.05)
    return size


def test_idle_work_imports_then_queues_one_item_per_mesh(tmp_path):
    report, _ = _report(tmp_path)
    work = idle_work(["json"], str(report))
    assert len(work) == 2  # the import, then reading the report
    work.pop(0)()
    work.pop(0)()
    assert len(work) == 1  # the one mesh the report names
    assert len(idle_work(["json"])) == 1


def test_a_waiting_worker_processes_the_meshes_and_forgets_them_when_one_changes(tmp_path):
    report, mesh = _report(tmp_path)
    pool = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        pool.warm(("mujoco",), meshes_from=report)
        size = _wait_until_cached(pool)
        # Unchanged, the mesh stays cached across steps: a second one joins it.
        other = mesh.with_name("other.obj")
        other.write_text(_cube())
        assert pool.run(f"{STEPS}:mesh_vertices", {"file": str(mesh)}, "m", None, 60) == {
            "vertices": 4
        }
        pool.run(f"{STEPS}:mesh_vertices", {"file": str(other)}, "m", None, 60)
        assert pool.run(f"{STEPS}:cache_size", {}, "size", None, 60)["bytes"] > size
        # Replaced by another mesh with the same timestamp (a rewrite within MuJoCo's
        # timestamp resolution): MuJoCo alone would compile the tetrahedron again.
        stamp = os.stat(mesh).st_mtime_ns
        replacement = mesh.with_name("new.obj")
        replacement.write_text(_cube())
        os.utime(replacement, ns=(stamp, stamp))
        os.replace(replacement, mesh)
        assert pool.run(f"{STEPS}:mesh_vertices", {"file": str(mesh)}, "m", None, 60) == {
            "vertices": 8
        }
    finally:
        pool.close()


def test_a_missing_report_or_mesh_is_skipped(tmp_path):
    from mjcfbuild.engine import worker_main

    report, mesh = _report(tmp_path)
    mesh.unlink()
    assert idle_work([], str(tmp_path / "no such report.json"))
    for source in (tmp_path / "no such report.json", report):
        work = idle_work([], str(source))
        while work:
            work.pop(0)()  # nothing raises
    assert str(mesh) not in worker_main._warmed
