"""The record of what builds wrote, which clean removes."""

from __future__ import annotations

import json

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.written import WRITTEN, record, recorded, written_file


def _ctx(arm) -> BuildContext:
    return BuildContext.from_manifest_file(arm / "robot.yaml", jobs=1, run_check=False)


def test_the_record_keeps_files_in_the_folder_and_grows(arm):
    ctx = _ctx(arm)
    ctx.state_dir.mkdir(parents=True)
    assert recorded(ctx) is None
    out = ctx.out_dir
    record(ctx, [out / "a.xml", out / "assets" / "m.obj", arm / "robot.yaml", ctx.state("x")])
    record(ctx, [str(out / "b.xml"), out / ".." / "mjcf" / "a.xml"])
    assert recorded(ctx) == ["a.xml", "assets/m.obj", "b.xml"]


def test_names_that_leave_the_folder_are_not_taken_from_the_record(arm):
    ctx = _ctx(arm)
    ctx.state_dir.mkdir(parents=True)
    names = ["../robot.yaml", "/etc/passwd", "assets/../../robot.yaml", "ok.xml", 3]
    ctx.state(WRITTEN).write_text(json.dumps({"files": names}))
    assert recorded(ctx) == ["ok.xml"]


def test_only_regular_files_reached_without_a_link_count(tmp_path):
    out = tmp_path / "out"
    (out / "assets").mkdir(parents=True)
    (out / "assets" / "m.obj").write_text("o")
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "m.obj").write_text("o")
    (out / "linked").symlink_to(outside)
    (out / "file_link.obj").symlink_to(outside / "m.obj")
    assert written_file(out, "assets/m.obj")
    assert not written_file(out, "linked/m.obj")
    assert not written_file(out, "file_link.obj")
    assert not written_file(out, "assets")
    assert not written_file(out, "missing.obj")
