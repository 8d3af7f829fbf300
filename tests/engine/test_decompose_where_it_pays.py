"""Decomposition only where it pays, in whole builds: a box keeps its hull, a U is decomposed;
figures per mesh in the output, the summary and the report; a new tolerance reruns only the
decompositions (and what reads them)."""

from __future__ import annotations

import json

import trimesh

import mjcfbuild
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.progress import Progress
from mjcfbuild.engine.runner import run_build
from mjcfbuild.meshes.objfile import obj_bytes
from tests.collision.test_concavity import u_shape
from tests.conftest import INERTIA, write

URDF = f"""<?xml version="1.0"?>
<robot name="shapes">
  <link name="base">{INERTIA}
    <visual><geometry><mesh filename="meshes/box.obj"/></geometry></visual>
  </link>
  <link name="cradle">{INERTIA}
    <visual><geometry><mesh filename="meshes/u.obj"/></geometry></visual>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="cradle"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"""


def robot(folder, tolerance=None):
    (folder / "meshes").mkdir(parents=True, exist_ok=True)
    box = trimesh.creation.box([0.3, 0.2, 0.1])
    (folder / "meshes" / "box.obj").write_bytes(obj_bytes(box.vertices, box.faces))
    u = u_shape()
    (folder / "meshes" / "u.obj").write_bytes(obj_bytes(u.vertices, u.faces))
    write(folder / "robot.urdf", URDF)
    decompose = "" if tolerance is None else f"\n  decompose: {{hull_tolerance: {tolerance}}}"
    return write(
        folder / "robot.yaml",
        "name: shapes\nsource:\n  urdf: robot.urdf\ncheck: {enabled: false}\n"
        f"collision:\n  default: decompose{decompose}\n",
    )


def summary(folder, name):
    return json.loads((folder / "mjcf/.mjcfbuild/decompositions" / f"{name}.json").read_text())


def parts(folder):
    return {p.name: p.read_bytes() for p in (folder / "mjcf/assets").glob("*part*.obj")}


def test_hull_where_close_coacd_elsewhere_with_figures(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    manifest = robot(tmp_path / "a")
    ctx = BuildContext.from_manifest_file(manifest, jobs=2)
    result = run_build(ctx, Progress(quiet=True))
    assert result.ok, result.errors
    box, u = summary(tmp_path / "a", "box"), summary(tmp_path / "a", "u")
    assert (box["method"], len(box["parts"])) == ("hull", 1)
    assert u["method"] == "coacd" and len(u["parts"]) >= 2
    assert u["concavity"] < u["hull_concavity"]
    assert u["coacd"]["preprocess_resolution"] == 20
    # The build's per-task line says how each mesh went.
    assert ctx.session.notes["decompose:box"].startswith("hull kept (0.000 <= 0.05)")
    assert (
        f"{len(u['parts'])} parts, concavity {u['concavity']:.3f}"
        in ctx.session.notes["decompose:u"]
    )
    # And so does the report.
    report = json.loads((tmp_path / "a/mjcf/report/report.json").read_text())
    rows = {row["name"]: row for row in report["decompositions"]}
    assert rows["box"]["method"] == "hull" and rows["u"]["parts"] == len(u["parts"])
    assert rows["u"]["concavity"] == u["concavity"]
    markdown = (tmp_path / "a/mjcf/report/report.md").read_text()
    assert "## Convex decompositions" in markdown
    assert f"| u | CoACD | {len(u['parts'])} |" in markdown
    produced = parts(tmp_path / "a")
    assert len(produced) == 1 + len(u["parts"])

    # Another folder, another cache, one job: the same bytes.
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "other-cache"))
    mjcfbuild.build(robot(tmp_path / "b"), jobs=1)
    assert parts(tmp_path / "b") == produced

    # A tolerance above the U's hull error: only the decompositions rerun (and their readers),
    # and the U keeps its hull now.
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    rerun = mjcfbuild.build(robot(tmp_path / "a", tolerance=0.5), jobs=2)
    assert sorted(rerun.ran) == ["assemble", "decompose:box", "decompose:u", "selfcollision"]
    assert summary(tmp_path / "a", "u")["method"] == "hull"


def test_mesh_and_decomposition_tasks_start_with_the_largest_mesh_file(tmp_path, monkeypatch):
    from mjcfbuild.engine.tasks import build_tasks

    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    manifest = robot(tmp_path)
    ctx = BuildContext.from_manifest_file(manifest, jobs=1)
    assert run_build(ctx, Progress(quiet=True)).ok  # the plan the task list is made from

    def started(kind: str) -> list[str]:
        names = [task["name"] for task in build_tasks(ctx)]
        return [name.partition(":")[2] for name in names if name.startswith(kind + ":")]

    sizes = {name: (tmp_path / "meshes" / f"{name}.obj").stat().st_size for name in ("box", "u")}
    assert sizes["u"] > sizes["box"]
    assert started("mesh") == started("decompose") == ["u", "box"]
    # A comment makes the box's file the larger: it goes first.
    with open(tmp_path / "meshes" / "box.obj", "a") as file:
        file.write("#" * sizes["u"] + "\n")
    assert started("mesh") == started("decompose") == ["box", "u"]
