"""The previews step keeps a picture only while its file is as the step left it."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.fsutil import md5_file
from mjcfbuild.steps.previews import pictures_in_place


def _folder_with_record(folder: Path) -> Path:
    pictures = folder / "previews"
    pictures.mkdir()
    entries = {}
    for name in ("three_quarter_visual.png", "side_visual.png", "three_quarter_collision.png"):
        (pictures / name).write_bytes(name.encode())
        entries[name] = {"shows": f"digest of {name}", "md5": md5_file(pictures / name)}
    record = folder / "previews.json"
    record.write_text(json.dumps(entries))
    return record


def test_pictures_as_recorded_are_in_place(tmp_path):
    record = _folder_with_record(tmp_path)
    assert pictures_in_place(tmp_path / "previews", record) == {
        "three_quarter_visual.png": "digest of three_quarter_visual.png",
        "side_visual.png": "digest of side_visual.png",
        "three_quarter_collision.png": "digest of three_quarter_collision.png",
    }


def test_a_picture_edited_or_removed_is_not(tmp_path):
    record = _folder_with_record(tmp_path)
    (tmp_path / "previews" / "three_quarter_visual.png").write_bytes(b"painted over")
    (tmp_path / "previews" / "side_visual.png").unlink()
    assert set(pictures_in_place(tmp_path / "previews", record)) == {"three_quarter_collision.png"}


def test_without_a_readable_record_nothing_is(tmp_path):
    record = _folder_with_record(tmp_path)
    for text in ("", "[1, 2]", '{"three_quarter_visual.png": {"md5": 3}}', "{not json"):
        record.write_text(text)
        assert pictures_in_place(tmp_path / "previews", record) == {}
    record.unlink()
    assert pictures_in_place(tmp_path / "previews", record) == {}
