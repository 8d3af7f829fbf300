"""The previews step keeps a picture only while its file is as the step left it, and says why
there are none: no OpenGL context (EGL), or what else failed."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.errors import EXIT_OK
from mjcfbuild.failpoints import VARIABLE
from mjcfbuild.fsutil import md5_file
from mjcfbuild.steps.previews import pictures_in_place
from tests.conftest import run_cli


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


def _build_warnings(arm: Path, tmp_path: Path, env: dict[str, str]) -> str:
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache"), **env}
    result = run_cli("build", "-q", cwd=arm, env=env)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    assert "Traceback" not in result.stderr
    return (arm / "mjcf" / "report" / "report.md").read_text()


def test_no_gl_context_is_blamed_on_egl(arm, tmp_path):
    """A GL context that cannot be made (here: an EGL device that does not exist)."""
    report = _build_warnings(arm, tmp_path, {"MUJOCO_EGL_DEVICE_ID": "99"})
    assert "no preview pictures: no OpenGL context to draw them in (" in report
    assert "MUJOCO_EGL_DEVICE_ID environment variable" in report and "libegl1" in report


def test_any_other_failure_while_drawing_says_what_it_is(arm, tmp_path):
    report = _build_warnings(arm, tmp_path, {VARIABLE: "previews-draw:raise"})
    assert (
        "no preview pictures: drawing them failed with RuntimeError: failpoint previews-draw"
        in (report)
    )
    assert "libegl" not in report and "OpenGL context" not in report
