"""Worker processes turn crashes and hangs into ordinary, named step failures."""

from __future__ import annotations

import pytest

from mjcfbuild.engine.workers import WorkerPool
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
