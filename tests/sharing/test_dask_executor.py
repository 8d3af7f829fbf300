"""Conversions and decompositions on a real Dask cluster (``distributed.LocalCluster``)."""

from __future__ import annotations

import os
import subprocess
import sys
from contextlib import contextmanager

import pytest

from mjcfbuild.errors import BuildFailed
from tests.sharing.conftest import PRODUCTS, free_port

distributed = pytest.importorskip("distributed")


@contextmanager
def local_cluster(**kwargs):
    """A cluster of worker processes on this machine. Its Nanny writes its workers' settings
    (MALLOC_TRIM_THRESHOLD_, OMP_NUM_THREADS) into this process's environment; they are put
    back after, so no later test in this process starts its processes with them."""
    saved = dict(os.environ)
    try:
        with distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
            host="127.0.0.1",
            **kwargs,
        ) as cluster:
            yield cluster
    finally:
        os.environ.clear()
        os.environ.update(saved)


@pytest.fixture(scope="module")
def cluster():
    """Two worker processes and a scheduler, for the module."""
    with local_cluster() as started:
        yield started


def executor(cluster) -> str:
    return cluster.scheduler_address.replace("tcp://", "dask://")


def test_cluster_results_land_in_the_caches_as_local_ones_do(
    cluster, machines, tmp_path, monkeypatch
):
    first, second = machines
    monkeypatch.setenv("MJCFBUILD_EXECUTOR", executor(cluster))
    monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", str(tmp_path / "shared"))
    first.build(monkeypatch)
    got = first.report()
    assert got["computed"] == {
        "decompose": {"here": 0, "on_cluster": 1},
        "mesh": {"here": 0, "on_cluster": 4},
    }
    assert got["uploaded"] == PRODUCTS and got["executor"] == executor(cluster)

    # The same robot built entirely on this machine gives the same bytes.
    monkeypatch.delenv("MJCFBUILD_EXECUTOR")
    monkeypatch.delenv("MJCFBUILD_CACHE_REMOTE")
    second.build(monkeypatch)
    assert second.report()["computed_here"] == PRODUCTS
    assert second.outputs() == first.outputs()


def test_a_lost_worker_task_runs_again_elsewhere(cluster, machines, tmp_path, monkeypatch):
    first, _ = machines
    monkeypatch.setenv("MJCFBUILD_EXECUTOR", executor(cluster))
    monkeypatch.setenv("MJCFBUILD_FAILPOINT", "cluster-decompose:kill-once")
    monkeypatch.setenv("MJCFBUILD_FAILPOINT_ONCE_DIR", str(tmp_path))
    result = first.build(monkeypatch)
    assert (tmp_path / "failpoint-cluster-decompose").exists()  # a worker was killed
    assert "decompose:upper_arm" in result.ran
    assert first.report()["computed_on_cluster"] == PRODUCTS


def test_a_task_whose_workers_keep_dying_fails_by_name(machines, monkeypatch):
    import dask

    first, _ = machines
    with dask.config.set({"distributed.scheduler.allowed-failures": 1}), local_cluster() as dying:
        monkeypatch.setenv("MJCFBUILD_EXECUTOR", executor(dying))
        monkeypatch.setenv("MJCFBUILD_FAILPOINT", "cluster-decompose:kill")
        with pytest.raises(BuildFailed) as info:
            first.build(monkeypatch)
    [error] = info.value.errors
    assert error.one_line().startswith("decompose:upper_arm: the Dask worker running it was lost")
    assert not (first.folder / "mjcf" / "example_arm.xml").exists()


def test_a_worker_with_other_versions_is_refused(machines, tmp_path, monkeypatch):
    first, _ = machines
    # A worker whose Python finds another CoACD release first.
    fake = tmp_path / "site" / "coacd-0.0.1.dist-info"
    fake.mkdir(parents=True)
    (fake / "METADATA").write_text("Metadata-Version: 2.1\nName: coacd\nVersion: 0.0.1\n")
    with distributed.LocalCluster(
        n_workers=0, processes=True, dashboard_address=":0", host="127.0.0.1"
    ) as scheduler:
        worker = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "distributed.cli.dask_worker",
                scheduler.scheduler_address,
                "--nthreads",
                "1",
                "--no-nanny",
                "--no-dashboard",
            ],
            env={**os.environ, "PYTHONPATH": str(fake.parent)},
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        try:
            with distributed.Client(scheduler) as client:
                client.wait_for_workers(1, timeout=60)
            monkeypatch.setenv("MJCFBUILD_EXECUTOR", executor(scheduler))
            with pytest.raises(BuildFailed) as info:
                first.build(monkeypatch)
        finally:
            worker.terminate()
            worker.wait()
    [error] = info.value.errors  # one error for the build, not one per task
    text = error.one_line()
    assert "coacd 0.0.1 (the build has" in text and "its results could not share" in text
    assert error.exit_code == 1


def test_an_unreachable_scheduler_is_a_warning(machines, monkeypatch):
    first, _ = machines
    monkeypatch.setenv("MJCFBUILD_EXECUTOR", f"dask://127.0.0.1:{free_port()}")
    monkeypatch.setenv("MJCFBUILD_DASK_CONNECT_TIMEOUT", "2")
    result = first.build(monkeypatch)
    assert any("cannot be reached" in w for w in result.warnings), result.warnings
    assert first.report()["computed_here"] == PRODUCTS
