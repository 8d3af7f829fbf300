"""Worker processes turn crashes and hangs into ordinary, named step failures."""

from __future__ import annotations

import threading
import time

import pytest

from mjcfbuild.engine.workers import HEAP_BLOCKS, WorkerPool
from mjcfbuild.errors import InputError, InternalError, TaskCrashed

STEPS = "tests.engine.misbehaving_steps"


@pytest.fixture
def pool(tmp_path):
    from tests.conftest import ROOT

    pool = WorkerPool(2, ROOT, tmp_path / "logs")
    yield pool
    pool.close()


def test_results_come_back_and_workers_are_reused(pool, tmp_path):
    first = pool.run(f"{STEPS}:echo", {"x": 1}, "echo", tmp_path / "a.log", timeout=60)
    second = pool.run(f"{STEPS}:echo", {"x": 2}, "echo", tmp_path / "b.log", timeout=60)
    assert first["x"] == 1 and second["x"] == 2
    assert first["pid"] == second["pid"]
    assert "C-level output" in (tmp_path / "a.log").read_text()


def test_segfault_fails_only_that_step_and_names_it(pool, tmp_path):
    with pytest.raises(TaskCrashed) as info:
        pool.run(f"{STEPS}:segfault", {}, "mesh:link3", tmp_path / "crash.log", timeout=60)
    text = info.value.one_line()
    assert "mesh:link3" in text and "SIGSEGV" in text
    assert "about to crash" in text  # the log's last line is quoted
    # the pool carries on with a fresh worker
    assert pool.run(f"{STEPS}:echo", {"ok": True}, "echo", None, timeout=60)["ok"]


def test_hang_is_stopped_at_the_time_limit(pool):
    with pytest.raises(TaskCrashed, match="did not finish within 1 s"):
        pool.run(f"{STEPS}:hang", {}, "decompose:x", None, timeout=1.0)


def test_errors_keep_their_class_and_location(pool):
    with pytest.raises(InputError) as info:
        pool.run(f"{STEPS}:input_error", {}, "mesh:m", None, timeout=60)
    assert info.value.one_line() == "m.stl:3: mesh is broken (fix it)"
    with pytest.raises(InternalError) as info:
        pool.run(f"{STEPS}:bug", {}, "mesh:m", None, timeout=60)
    assert "ValueError: unexpected" in info.value.message
    assert "Traceback" in info.value.details


def test_a_worker_imports_while_idle_and_a_request_waits_for_one_import_at_most(
    tmp_path, monkeypatch
):
    import os
    import sys

    from mjcfbuild.engine.worker_main import idle_work, requests

    read, write = os.pipe()
    monkeypatch.setenv("PROBE_FD", str(write))
    monkeypatch.delitem(sys.modules, "tests.engine.preload_probe", raising=False)
    os.write(write, b'{"step": "first"}\n')
    preload = idle_work(["tests.engine.preload_probe", "tests.engine.slow_import"])
    lines = requests(read, preload)
    # a request is waiting: it is served before anything is imported
    assert next(lines) == b'{"step": "first"}'
    assert "tests.engine.preload_probe" not in sys.modules
    # idle: the probe is imported, and the request it sends is served before the next import
    assert next(lines) == b'{"step": "after the probe"}'
    assert "tests.engine.preload_probe" in sys.modules
    assert len(preload) == 1  # the slow import is still to come
    os.close(write)
    os.close(read)


def test_warm_starts_every_worker_and_steps_use_them(tmp_path):
    from tests.conftest import ROOT

    pool = WorkerPool(2, ROOT, tmp_path / "logs")
    try:
        pool.warm(("json",))
        pool.warm(("json",))  # never more than the pool's size
        started = {worker.process.pid for worker in pool._all}
        assert len(started) == 2
        pids = {pool.run(f"{STEPS}:echo", {}, "echo", None, timeout=60)["pid"] for _ in range(3)}
        assert pids <= started
    finally:
        pool.close()


def test_close_stops_every_worker_at_once(tmp_path):
    from tests.conftest import ROOT

    # each worker spends a minute importing: close must not wait for that, used or not
    pool = WorkerPool(2, ROOT, tmp_path / "logs")
    pool.warm(("tests.engine.slow_import",))
    workers = list(pool._all)
    pool.close()
    assert [worker.process.returncode for worker in workers] == [-9, -9]


def test_a_step_goes_to_the_idle_worker_that_preloads_its_module(tmp_path):
    from tests.conftest import ROOT

    pool = WorkerPool(2, ROOT, tmp_path / "logs")
    try:
        pool.warm((STEPS,), count=1)
        pool.warm(("json",), count=2)  # a second worker, preloading something else
        preloads = {worker.process.pid: worker.preload for worker in pool._all}
        assert len(preloads) == 2
        # Whichever worker was started or released last, the step's module decides.
        for _ in range(3):
            pid = pool.run(f"{STEPS}:echo", {}, "echo", None, timeout=60)["pid"]
            assert preloads[pid] == (STEPS,)
    finally:
        pool.close()


def test_a_worker_killed_while_idle_is_replaced(tmp_path):
    import threading

    from tests.conftest import ROOT

    pool = WorkerPool(1, ROOT, tmp_path / "logs")
    try:
        first = pool.run(f"{STEPS}:echo", {}, "echo", None, timeout=60)["pid"]
        [worker] = pool._all
        worker.process.kill()
        worker.process.wait()
        # Run in a thread so that a pool still counting the dead worker fails here, not hangs.
        results: list[int] = []
        thread = threading.Thread(
            target=lambda: results.append(
                pool.run(f"{STEPS}:echo", {}, "echo", None, timeout=60)["pid"]
            ),
            daemon=True,
        )
        thread.start()
        thread.join(timeout=60)
        assert results and results[0] != first
    finally:
        pool.close()


def _in_thread(function) -> tuple[threading.Thread, list]:
    results: list = []
    thread = threading.Thread(target=lambda: results.append(function()), daemon=True)
    thread.start()
    return thread, results


def _wait_for(condition) -> None:
    """Wait (up to a minute, for slow machines) until ``condition()`` holds."""
    deadline = time.monotonic() + 60
    while not condition():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.01)


@pytest.fixture
def two_workers(tmp_path):
    from tests.conftest import ROOT

    pool = WorkerPool(2, ROOT, tmp_path / "logs")
    pool.warm((STEPS,))  # both preload the same: only the affinity decides
    yield pool
    pool.close()


def test_steps_of_one_model_follow_the_worker_that_ran_one(two_workers, tmp_path):
    pool = two_workers
    holder = pool.run(f"{STEPS}:echo", {}, "assemble", None, 60, affinity="robot.xml")["pid"]
    for _ in range(3):
        pool.run(f"{STEPS}:echo", {}, "mesh:m", None, 60)  # steps of no model go anywhere
        assert pool.run(f"{STEPS}:echo", {}, "check", None, 60, affinity="robot.xml")["pid"] == (
            holder
        )
    # While the holder runs a step of the model, the next one waits for it, though the other
    # worker is idle: MuJoCo would process every mesh again there.
    until = tmp_path / "go"
    first, first_pid = _in_thread(
        lambda: pool.run(f"{STEPS}:pause", {"until": str(until)}, "check", None, 60, "robot.xml")
    )
    _wait_for(lambda: any(w.running == "robot.xml" for w in pool._all))
    second, second_pid = _in_thread(
        lambda: pool.run(f"{STEPS}:echo", {}, "previews", None, 60, affinity="robot.xml")
    )
    _wait_for(lambda: len(pool._condition._waiters) == 1)  # type: ignore[attr-defined]
    assert second.is_alive()
    # Another model's step takes the idle worker meanwhile.
    other = pool.run(f"{STEPS}:echo", {}, "assemble", None, 60, affinity="other.xml")["pid"]
    assert other != holder
    until.touch()
    first.join(60)
    second.join(60)
    assert first_pid == [{"pid": holder}]
    assert second_pid[0]["pid"] == holder


def test_warm_for_prepares_a_second_worker_for_the_model(two_workers, tmp_path):
    pool = two_workers
    holder = pool.run(f"{STEPS}:echo", {}, "assemble", None, 60, affinity="robot.xml")["pid"]
    pool.warm_for("robot.xml", f"{STEPS}:echo", {}, 60)
    _wait_for(lambda: all(w.holds == "robot.xml" for w in pool._all) and len(pool._idle) == 2)
    # Both hold the model now: two of its steps run side by side.
    until = tmp_path / "go"
    first, first_pid = _in_thread(
        lambda: pool.run(f"{STEPS}:pause", {"until": str(until)}, "check", None, 60, "robot.xml")
    )
    _wait_for(lambda: len(pool._idle) == 1)
    second = pool.run(f"{STEPS}:echo", {}, "previews", None, 60, affinity="robot.xml")["pid"]
    until.touch()
    first.join(60)
    assert {first_pid[0]["pid"], second} == {w.process.pid for w in pool._all}
    assert holder in {first_pid[0]["pid"], second}
    # A warm that fails leaves the worker usable, holding nothing new.
    pool.warm_for("third.xml", f"{STEPS}:bug", {}, 60)
    _wait_for(lambda: len(pool._idle) == 2)
    assert not any(w.holds == "third.xml" for w in pool._all)
    assert pool.run(f"{STEPS}:echo", {}, "echo", None, 60)["pid"] in {second, first_pid[0]["pid"]}


def test_a_step_waits_for_the_warm_up_preparing_a_worker_for_it(two_workers, tmp_path):
    """In a first build the assembly waits for the worker warmed for it while the matrix ran,
    rather than take the matrix's worker, which has only the collision meshes loaded."""
    pool = two_workers
    holder = pool.run(f"{STEPS}:echo", {}, "matrix", None, 60, affinity="robot.xml")["pid"]
    until = tmp_path / "go"
    pool.warm_for("robot.xml", f"{STEPS}:pause", {"until": str(until)}, 60, prepares=(STEPS,))
    _wait_for(lambda: any(w.preparing for w in pool._all))
    waiting, pid = _in_thread(
        lambda: pool.run(f"{STEPS}:echo", {}, "assemble", None, 60, affinity="robot.xml")
    )
    _wait_for(lambda: len(pool._condition._waiters) == 1)  # type: ignore[attr-defined]
    assert waiting.is_alive() and len(pool._idle) == 1  # the holder is idle, and not taken
    until.touch()
    waiting.join(60)
    prepared = [w for w in pool._all if w.process.pid != holder]
    assert pid == [{"pid": prepared[0].process.pid}]
    assert prepared[0].holds == "robot.xml" and not prepared[0].preparing


def test_a_warm_up_started_with_a_step_never_takes_the_steps_worker(two_workers, tmp_path):
    """The matrix prepares the assembly's worker once it has its own: with the other worker
    busy (a mesh still converting), the warm-up finds none and the matrix does not wait."""
    pool = two_workers
    until = tmp_path / "go"
    busy, _ = _in_thread(
        lambda: pool.run(f"{STEPS}:pause", {"until": str(until)}, "mesh:m", None, 60)
    )
    _wait_for(lambda: len(pool._idle) == 1)
    took: list[bool] = []

    def prepare() -> None:
        took.append(pool.warm_for("robot.xml", f"{STEPS}:echo", {}, 60, prepares=(STEPS,)))

    pool.run(f"{STEPS}:echo", {}, "matrix", None, 60, affinity="robot.xml", started=prepare)
    assert took == [False]
    until.touch()
    busy.join(60)


def test_the_checks_warm_up_may_take_a_holder_no_warm_up_prepared(two_workers, tmp_path):
    """In a first build the matrix's worker holds the model with its collision meshes only:
    the check's warm-up may take it (``holders_too``), never the worker a warm-up prepared."""
    pool = two_workers
    matrix = pool.run(f"{STEPS}:echo", {}, "matrix", None, 60, affinity="robot.xml")["pid"]
    assert pool.warm_for("robot.xml", f"{STEPS}:echo", {}, 60, prepares=(STEPS,))
    _wait_for(lambda: len(pool._idle) == 2 and all(w.holds == "robot.xml" for w in pool._all))
    assert not pool.warm_for("robot.xml", f"{STEPS}:echo", {}, 60)  # every idle one holds it
    until = tmp_path / "go"
    assert pool.warm_for("robot.xml", f"{STEPS}:pause", {"until": str(until)}, 60, holders_too=True)
    [taken] = [w for w in pool._all if w not in pool._idle]
    assert taken.process.pid == matrix and not taken.prepared
    until.touch()
    _wait_for(lambda: len(pool._idle) == 2)


def test_a_kept_warm_up_takes_the_next_worker_to_fall_idle(two_workers, tmp_path):
    """The matrix started while the other worker still converts a mesh: the assembly's
    warm-up waits for that worker to fall idle, then prepares it."""
    pool = two_workers
    mesh, matrix = tmp_path / "mesh", tmp_path / "matrix"
    busy, _ = _in_thread(lambda: pool.run(f"{STEPS}:pause", {"until": str(mesh)}, "m", None, 60))
    _wait_for(lambda: len(pool._idle) == 1)
    took: list[bool] = []

    def prepare() -> None:
        took.append(pool.warm_for("robot.xml", f"{STEPS}:echo", {}, 60, (STEPS,), until_idle=True))

    running, ran = _in_thread(
        lambda: pool.run(
            f"{STEPS}:pause", {"until": str(matrix)}, "matrix", None, 60, "robot.xml", prepare
        )
    )
    _wait_for(lambda: took == [False])  # both busy: kept for the mesh's worker
    mesh.touch()
    busy.join(60)
    _wait_for(lambda: any(w.prepared == (STEPS,) for w in pool._all))
    matrix.touch()
    running.join(60)
    [prepared] = [w for w in pool._all if w.prepared]
    assert prepared.process.pid != ran[0]["pid"] and prepared.holds == "robot.xml"


def test_a_kept_warm_up_yields_to_a_waiting_step_and_can_be_forgotten(two_workers, tmp_path):
    """A worker that falls idle while a step waits for one goes to the step (the warm-up
    takes the next one to fall idle unclaimed); one forgotten takes none."""
    pool = two_workers
    first, second = tmp_path / "first", tmp_path / "second"
    one, _ = _in_thread(lambda: pool.run(f"{STEPS}:pause", {"until": str(first)}, "a", None, 60))
    two, _ = _in_thread(lambda: pool.run(f"{STEPS}:pause", {"until": str(second)}, "b", None, 60))
    _wait_for(lambda: not pool._idle and len(pool._all) == 2)
    assert not pool.warm_for("robot.xml", f"{STEPS}:echo", {}, 60, until_idle=True)
    gate = tmp_path / "gate"
    waiting, _ = _in_thread(lambda: pool.run(f"{STEPS}:pause", {"until": str(gate)}, "c", None, 60))
    _wait_for(lambda: pool._steps_waiting == 1)
    first.touch()
    _wait_for(lambda: pool._steps_waiting == 0)
    assert pool._waiting_warm_up is not None  # the freed worker went to the waiting step
    pool.forget_warm_up()
    second.touch()
    gate.touch()
    for thread in (one, two, waiting):
        thread.join(60)
    _wait_for(lambda: len(pool._idle) == 2)
    assert not any(w.holds == "robot.xml" for w in pool._all)


def test_a_step_waits_for_the_workers_starting_in_the_background(tmp_path):
    """A step that comes while the command's workers are still starting takes one of them
    (importing its module) rather than starting a worker of its own, and the pool never
    holds more workers than its size."""
    from tests.conftest import ROOT

    pool = WorkerPool(2, ROOT, tmp_path / "logs")
    try:
        pool.warm_in_background(((STEPS,), 1, None), (("json",), 2, None))
        pid = pool.run(f"{STEPS}:echo", {}, "echo", None, timeout=60)["pid"]
        pool.wait_started()
        preloads = {worker.process.pid: worker.preload for worker in pool._all}
        assert sorted(preloads.values()) == [("json",), (STEPS,)]
        assert preloads[pid] == (STEPS,)
    finally:
        pool.close()


def test_a_pool_closed_while_its_workers_start_keeps_none(tmp_path):
    from tests.conftest import ROOT

    pool = WorkerPool(2, ROOT, tmp_path / "logs")
    pool.warm_in_background((("json",), None, None))
    pool.close()
    pool.wait_started()
    assert pool._all == [] and pool._idle == []


def test_a_worker_keeps_freed_model_sized_blocks_for_the_next_compile(pool, tmp_path, monkeypatch):
    # MuJoCo's compiles allocate and free tens of megabytes each; glibc unmaps blocks that
    # large when freed and faults fresh pages in for the next compile (a third of a compile's
    # time on g1, docs/benchmarks.md). The workers start with the heap keeping them, unless
    # the environment sets the variables: a dask Nanny started in this process (the cluster
    # tests) puts MALLOC_TRIM_THRESHOLD_=65536 into os.environ, which the workers would keep.
    for variable in ("MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_"):
        monkeypatch.delenv(variable, raising=False)
    settings = pool.run(f"{STEPS}:allocator", {}, "allocator", tmp_path / "a.log", 60)
    assert settings == {
        "MALLOC_MMAP_THRESHOLD_": str(HEAP_BLOCKS),
        "MALLOC_TRIM_THRESHOLD_": str(HEAP_BLOCKS),
    }
