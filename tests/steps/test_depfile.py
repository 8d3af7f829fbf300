"""Depfiles: dependencies a step only discovers while running."""

from __future__ import annotations

from mjcfbuild.steps.depfile import Depfile


def test_round_trip_and_staleness(tmp_path):
    present = tmp_path / "inc.xacro"
    present.write_text("x")
    absent = tmp_path / "optional.xacro"
    depfile = Depfile([str(present)], [str(absent)], {"ROBOT_VARIANT": "a"})
    depfile.write(tmp_path / "deps.json")
    read = Depfile.read(tmp_path / "deps.json")
    assert read == depfile
    assert read.stale_reason({"ROBOT_VARIANT": "a"}) is None
    assert "ROBOT_VARIANT" in read.stale_reason({"ROBOT_VARIANT": "b"})
    absent.write_text("now here")
    assert "now exists" in read.stale_reason({"ROBOT_VARIANT": "a"})
    present.unlink()
    assert "was removed" in read.stale_reason({"ROBOT_VARIANT": "a"})


def test_unreadable_depfile_is_none(tmp_path):
    (tmp_path / "deps.json").write_text("{broken")
    assert Depfile.read(tmp_path / "deps.json") is None
    assert Depfile.read(tmp_path / "missing.json") is None
