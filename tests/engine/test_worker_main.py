"""A worker process processes the previous model's meshes while it waits, and never lets
MuJoCo's cache hand a step a mesh that has changed since."""

from __future__ import annotations

import importlib
import json
import os
import sys
from collections.abc import Callable
from pathlib import Path

from mjcfbuild.engine import worker_main
from mjcfbuild.engine.worker_main import drop_mesh_work, idle_work
from tests.conftest import file_clock_past
from tests.engine.mujoco_steps import cache_size, mesh_vertices


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


class _Worker:
    """What a worker process does with MuJoCo, in this process: its idle work until the
    first step (all of it: a real worker does it while no step is waiting), then steps."""

    def __init__(self, report: Path) -> None:
        import mujoco

        mujoco.mj_clearCache(mujoco.mj_getCache())
        worker_main._warmed.clear()
        self.idle = idle_work(["mujoco"], str(report))
        while self.idle:
            self.idle.pop(0)()

    def step(self, function: Callable[[dict], dict], payload: dict) -> dict:
        drop_mesh_work(self.idle)
        worker_main.forget_changed_meshes()
        return function(payload)


def test_idle_work_imports_then_queues_one_item_per_mesh(tmp_path):
    report, _ = _report(tmp_path)
    work = idle_work(["json"], str(report))
    assert len(work) == 2  # the import, then reading the report
    work.pop(0)()
    work.pop(0)()
    assert len(work) == 1  # the one mesh the report names
    assert len(idle_work(["json"])) == 1


def test_the_first_step_ends_the_mesh_work_but_not_the_imports(tmp_path):
    report, _ = _report(tmp_path)
    work = idle_work(["json", "csv"], str(report))
    work.pop(0)()
    drop_mesh_work(work)
    assert [item.args for item in work] == [("csv",)]
    work = idle_work(["json"], str(report))
    work.pop(0)()
    work.pop(0)()  # the report is read: one item per mesh
    drop_mesh_work(work)
    assert work == []


def test_a_waiting_worker_processes_the_meshes_and_forgets_them_when_one_changes(tmp_path):
    report, mesh = _report(tmp_path)
    worker = _Worker(report)
    size = worker.step(cache_size, {})["bytes"]
    assert size > 0
    # Unchanged, the mesh stays cached across steps: a second one joins it.
    other = mesh.with_name("other.obj")
    other.write_text(_cube())
    assert worker.step(mesh_vertices, {"file": str(mesh)}) == {"vertices": 4}
    worker.step(mesh_vertices, {"file": str(other)})
    assert worker.step(cache_size, {})["bytes"] > size
    # Replaced by another mesh with the same timestamp (a rewrite within MuJoCo's
    # timestamp resolution): MuJoCo alone would compile the tetrahedron again.
    stamp = os.stat(mesh).st_mtime_ns
    replacement = mesh.with_name("new.obj")
    replacement.write_text(_cube())
    os.utime(replacement, ns=(stamp, stamp))
    os.replace(replacement, mesh)
    assert worker.step(mesh_vertices, {"file": str(mesh)}) == {"vertices": 8}


def test_a_mesh_rewritten_in_place_with_its_size_and_time_kept_is_read_again(tmp_path):
    """Same inode, same size, its time restored (``cp -p``, ``rsync -a`` onto the file): only
    the status-change time tells, and the worker empties MuJoCo's cache for it."""
    report, mesh = _report(tmp_path)
    tetrahedron = _tetrahedron()
    mesh.write_text(tetrahedron + "#" * (len(_cube()) - len(tetrahedron) - 1) + "\n")
    before = os.stat(mesh)
    worker = _Worker(report)
    assert worker.step(mesh_vertices, {"file": str(mesh)}) == {"vertices": 4}
    file_clock_past(tmp_path, before.st_ctime_ns)
    with open(mesh, "r+") as handle:  # in place: the same inode
        handle.write(_cube())
    os.utime(mesh, ns=(before.st_atime_ns, before.st_mtime_ns))
    after = os.stat(mesh)
    assert (after.st_ino, after.st_size, after.st_mtime_ns) == (
        before.st_ino,
        before.st_size,
        before.st_mtime_ns,
    )
    assert worker.step(mesh_vertices, {"file": str(mesh)}) == {"vertices": 8}


def test_a_mesh_changed_in_another_second_is_reread_without_emptying_the_cache(tmp_path):
    report, mesh = _report(tmp_path)
    worker = _Worker(report)
    warmed = worker.step(cache_size, {})["bytes"]
    other = mesh.with_name("other.obj")
    other.write_text(_cube())
    worker.step(mesh_vertices, {"file": str(other)})
    cube = worker.step(cache_size, {})["bytes"] - warmed
    # A time two seconds later, as a rebuild writes it: MuJoCo sees the change itself.
    later = os.stat(mesh).st_mtime_ns + 2_000_000_000
    replacement = mesh.with_name("new.obj")
    replacement.write_text(_cube())
    os.utime(replacement, ns=(later, later))
    os.replace(replacement, mesh)
    assert worker.step(mesh_vertices, {"file": str(mesh)}) == {"vertices": 8}
    # Both cubes are cached: the unchanged one was kept (emptying would leave one).
    assert worker.step(cache_size, {})["bytes"] >= 2 * cube


def test_a_missing_report_or_mesh_is_skipped(tmp_path):
    report, mesh = _report(tmp_path)
    mesh.unlink()
    assert idle_work([], str(tmp_path / "no such report.json"))
    for source in (tmp_path / "no such report.json", report):
        work = idle_work([], str(source))
        while work:
            work.pop(0)()  # nothing raises
    assert str(mesh) not in worker_main._warmed


def test_a_module_edited_with_its_size_and_time_kept_is_a_code_change(tmp_path, monkeypatch):
    """A worker must not serve a build with a module that changed after it was imported, even
    when the edit kept its size and had its time restored."""
    module = tmp_path / "probe_module_44.py"
    module.write_text("VALUE = 1\n")
    file_clock_past(tmp_path, os.stat(module).st_ctime_ns)
    watch = worker_main._CodeWatch()  # this process "started" after the module was written
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        importlib.import_module("probe_module_44")
        watch.note()
    finally:
        sys.modules.pop("probe_module_44", None)
    assert watch.changed() is None
    before = os.stat(module)
    file_clock_past(tmp_path, before.st_ctime_ns)
    module.write_text("VALUE = 2\n")
    os.utime(module, ns=(before.st_atime_ns, before.st_mtime_ns))
    assert watch.changed() == str(module)
