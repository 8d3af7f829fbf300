"""The record of what builds wrote, which clean removes."""

from __future__ import annotations

import json

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.written import (
    WRITTEN,
    edited,
    record,
    recorded,
    remove_written,
    written_file,
)
from mjcfbuild.fsutil import md5_file


def _ctx(arm) -> BuildContext:
    return BuildContext.from_manifest_file(arm / "robot.yaml", jobs=1, run_check=False)


def test_the_record_keeps_files_in_the_folder_and_grows(arm):
    ctx = _ctx(arm)
    ctx.state_dir.mkdir(parents=True)
    assert recorded(ctx) is None
    out = ctx.out_dir
    for name in ("a.xml", "assets/m.obj", "b.xml", ".mjcfbuild/x"):
        (out / name).parent.mkdir(parents=True, exist_ok=True)
        (out / name).write_text(name)
    record(ctx, [out / "a.xml", out / "assets" / "m.obj", arm / "robot.yaml", ctx.state("x")])
    record(ctx, [str(out / "b.xml"), out / ".." / "mjcf" / "a.xml", out / "never_written.xml"])
    assert recorded(ctx) == {
        "a.xml": md5_file(out / "a.xml"),
        "assets/m.obj": md5_file(out / "assets/m.obj"),
        "b.xml": md5_file(out / "b.xml"),
    }


def test_an_edited_file_the_build_did_not_vouch_for_keeps_what_the_build_wrote(arm):
    """A target of a task that failed, which the user had edited: still not the build's bytes;
    an entry of a file that is gone goes."""
    ctx = _ctx(arm)
    ctx.state_dir.mkdir(parents=True)
    out = ctx.out_dir
    (out / "model.xml").write_text("built")
    (out / "gone.xml").write_text("built")
    record(ctx, [out / "model.xml", out / "gone.xml"])
    built = md5_file(out / "model.xml")
    (out / "model.xml").write_text("edited by hand")
    (out / "gone.xml").unlink()
    (out / "new.xml").write_text("from a task that failed half way")
    record(ctx, [], owned=[out / "model.xml", out / "new.xml"])
    assert recorded(ctx) == {"model.xml": built, "new.xml": md5_file(out / "new.xml")}
    assert edited(out, "model.xml", built) and not edited(out, "new.xml", None)


def test_a_record_of_names_alone_is_read(arm):
    ctx = _ctx(arm)
    ctx.state_dir.mkdir(parents=True)
    ctx.state(WRITTEN).write_text(json.dumps({"files": ["b.xml", "a.xml"]}))
    assert recorded(ctx) == {"a.xml": None, "b.xml": None}


def test_names_that_leave_the_folder_are_not_taken_from_the_record(arm):
    ctx = _ctx(arm)
    ctx.state_dir.mkdir(parents=True)
    names = ["../robot.yaml", "/etc/passwd", "assets/../../robot.yaml", "ok.xml", 3]
    ctx.state(WRITTEN).write_text(json.dumps({"files": names}))
    assert list(recorded(ctx) or {}) == ["ok.xml"]
    ctx.state(WRITTEN).write_text(json.dumps({"files": {"../x": "0", "ok.xml": 3}}))
    assert recorded(ctx) == {"ok.xml": None}


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


def test_removing_a_folder_the_build_wrote_keeps_an_edited_file(arm):
    ctx = _ctx(arm)
    ctx.state_dir.mkdir(parents=True)
    page = ctx.out_dir / "report" / "page"
    page.mkdir(parents=True)
    (page / "tables.js").write_text("built")
    (page / "app.js").write_text("built")
    record(ctx, [page / "tables.js", page / "app.js"])
    (page / "app.js").write_text("edited by hand")
    assert remove_written(ctx, page) == ["report/page/tables.js"]
    assert (page / "app.js").read_text() == "edited by hand"
