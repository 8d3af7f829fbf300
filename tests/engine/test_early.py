"""A build starts its workers before reading the manifest: a rebuild's from the last build's
stamp, a first build's for its mesh steps; the build uses them."""

from __future__ import annotations

import shutil

import pytest

import mjcfbuild
from mjcfbuild.cli import run
from mjcfbuild.engine.early import start_workers
from mjcfbuild.engine.session import BuildSession
from mjcfbuild.engine.workers import MESH_MODULES, first_build_preloads, rebuild_preloads
from tests.conftest import copy_example


@pytest.fixture
def built_arm(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    folder = copy_example("arm", tmp_path)
    assert run(["build", str(folder / "robot.yaml"), "-j", "2", "-q"]) == 0  # leaves a stamp
    return folder


def test_the_workers_of_a_rebuild_start_from_the_stamp(built_arm):
    state = built_arm / "mjcf" / ".mjcfbuild"
    pool = start_workers(built_arm / "robot.yaml", run_check=True, jobs=2)
    try:
        pool.wait_started()
        assert pool.cwd == built_arm and pool.log_dir == state / "logs"
        assert [w.preload for w in pool._all] == list(rebuild_preloads(True))
        assert [w.meshes_from for w in pool._all] == [state / "assembly.json"] * 2
    finally:
        pool.close()
    # The stamp of a build with the check says nothing about one without it.
    _assert_first_build_workers(start_workers(built_arm / "robot.yaml", run_check=False, jobs=2))


def _assert_first_build_workers(pool) -> None:
    """``pool`` is a first build's: two workers importing the mesh step's modules first, then
    MuJoCo and the matrix's or the assembly's step, what they print kept in the cache
    folder's logs (the build's state folder is not known yet)."""
    try:
        pool.wait_started()
        first, second = first_build_preloads()
        assert [w.preload for w in pool._all] == [first, second]
        assert first[: len(MESH_MODULES)] == second[: len(MESH_MODULES)] == MESH_MODULES
        assert first[-1] == "mjcfbuild.steps.selfcollision"
        assert second[-1] == "mjcfbuild.steps.assemble"
        assert [w.meshes_from for w in pool._all] == [None, None]
        assert pool.log_dir.name == "logs" and pool.log_dir.parent.name == "cache"
    finally:
        pool.close()


def test_after_a_mesh_edit_the_mesh_worker_only_imports(built_arm):
    state = built_arm / "mjcf" / ".mjcfbuild"
    mesh = built_arm / "meshes" / "forearm.obj"
    mesh.write_text(mesh.read_text().replace(" 0.240000", " 0.250000"))
    pool = start_workers(built_arm / "robot.yaml", run_check=True, jobs=2)
    try:
        pool.wait_started()
        assert [w.meshes_from for w in pool._all] == [state / "assembly.json", None]
    finally:
        pool.close()


def test_first_build_workers_without_a_stamp_or_its_folder(built_arm, tmp_path):
    other = copy_example("arm", tmp_path / "other")
    _assert_first_build_workers(start_workers(other / "robot.yaml", run_check=True, jobs=2))
    shutil.rmtree(built_arm / "mjcf")
    _assert_first_build_workers(start_workers(built_arm / "robot.yaml", run_check=True, jobs=2))
    assert not (built_arm / "mjcf").exists()  # nothing made where the old build was


def test_a_rebuild_adopts_them_and_builds_what_a_fresh_build_does(built_arm, tmp_path):
    adopted: list[bool] = []
    adopt = BuildSession.adopt

    def recording_adopt(self, pool):
        adopted.append(adopt(self, pool))
        return adopted[-1]

    mesh = built_arm / "meshes" / "forearm.obj"
    mesh.write_text(mesh.read_text().replace(" 0.240000", " 0.250000"))  # a longer forearm
    damped = (
        (built_arm / "urdf" / "arm.urdf.xacro")
        .read_text()
        .replace('damping="0.5"', 'damping="0.7"', 1)
    )
    (built_arm / "urdf" / "arm.urdf.xacro").write_text(damped)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(BuildSession, "adopt", recording_adopt)
        assert run(["build", str(built_arm / "robot.yaml"), "-j", "2", "-q"]) == 0
    assert adopted == [True]
    # The same edits built from nothing give the same files.
    fresh = copy_example("arm", tmp_path / "fresh")
    shutil.copy(mesh, fresh / "meshes" / "forearm.obj")
    (fresh / "urdf" / "arm.urdf.xacro").write_text(damped)
    assert mjcfbuild.build(fresh / "robot.yaml", jobs=2).ok
    # (Whether a worker processed the old forearm before the build rewrote it depends on
    # timing; test_worker_main covers that case deterministically.)
    for name in ("example_arm.xml", "scene.xml", ".mjcfbuild/assembly.json"):
        assert (built_arm / "mjcf" / name).read_bytes() == (fresh / "mjcf" / name).read_bytes()


def test_a_cache_folder_that_cannot_be_written_leaves_the_workers_to_the_build(
    tmp_path, monkeypatch
):
    """A first build's early workers print to the cache folder: where it cannot be made, the
    build starts its own workers, and builds (a read-only cache never fails a build)."""
    blocker = tmp_path / "a file"
    blocker.write_text("")
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(blocker / "cache"))
    folder = copy_example("arm", tmp_path)
    assert start_workers(folder / "robot.yaml", run_check=False, jobs=2) is None
    assert run(["build", str(folder / "robot.yaml"), "-j", "2", "-q", "--no-check"]) == 0


def test_a_first_build_with_more_jobs_starts_the_rest_with_the_mesh_step_only(tmp_path):
    """Only two model steps are due at once; the other workers convert meshes."""
    folder = copy_example("arm", tmp_path / "arm")
    pool = start_workers(folder / "robot.yaml", run_check=True, jobs=4)
    try:
        pool.wait_started()
        assert [w.preload for w in pool._all] == [
            *first_build_preloads(),
            MESH_MODULES,
            MESH_MODULES,
        ]
    finally:
        pool.close()
    pool = start_workers(folder / "robot.yaml", run_check=True, jobs=1)
    try:
        pool.wait_started()
        assert [w.preload for w in pool._all] == [first_build_preloads()[0]]
    finally:
        pool.close()
