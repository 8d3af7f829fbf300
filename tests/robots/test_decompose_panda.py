"""Decomposition acceptance on a real robot: a panda link, decomposed with CoACD."""

from __future__ import annotations

import pytest

import mjcfbuild
from bench import robot_data
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.progress import Progress
from mjcfbuild.engine.runner import run_build

pytestmark = [pytest.mark.robots, pytest.mark.slow]

RULE = "collision:\n  rules:\n    - links: [panda_link4]\n      policy: decompose\n      decompose: {threshold: %s}\n"


def manifest(folder, threshold):
    robot = robot_data.ROBOTS["panda"]
    urdf = robot_data.unpack(robot)
    return robot_data.manifest(robot, folder, urdf, robot_data.package_root(), RULE % threshold)


def parts(folder):
    return {p.name: p.read_bytes() for p in (folder / "mjcf" / "assets").glob("*_part*.obj")}


def test_panda_link_decomposition(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache-a"))
    first = manifest(tmp_path / "a", 0.05)
    assert "decompose:collision_link4" in mjcfbuild.build(first, jobs=2).ran
    produced = parts(tmp_path / "a")
    assert produced

    # The same bytes again, computed afresh (another cache).
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache-b"))
    mjcfbuild.build(manifest(tmp_path / "b", 0.05), jobs=2)
    assert parts(tmp_path / "b") == produced

    # A second output folder from the same meshes: no CoACD time, the cache answers.
    ctx = BuildContext.from_manifest_file(manifest(tmp_path / "c", 0.05), jobs=2)
    run_build(ctx, Progress(quiet=True))
    assert ctx.session.notes["decompose:collision_link4"].startswith("from cache; ")
    assert parts(tmp_path / "c") == produced

    # A new threshold reruns that decomposition and the assembly only.
    changed = manifest(tmp_path / "a", 0.08)
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache-a"))
    assert sorted(mjcfbuild.build(changed, jobs=2).ran) == [
        "assemble",
        "decompose:collision_link4",
        "selfcollision",
    ]
