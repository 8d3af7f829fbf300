"""The previews step keeps a picture only while its file is as the step left it, and says why
there are none: no OpenGL context (EGL), or what else failed."""

from __future__ import annotations

import json
import re
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


def _pictures(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in (folder / "mjcf/report/previews").glob("*.png")}


def test_pictures_drawn_in_one_folder_are_taken_from_the_cache_in_another(tmp_path):
    """Another folder of the same robot takes the pictures (and the reference kinematics) from
    the shared cache, byte for byte, drawing nothing: a drawing would fail here. An entry that
    is not as it was stored is drawn again."""
    from tests.conftest import copy_example

    cache = tmp_path / "cache"
    first = copy_example("arm", tmp_path / "first")
    drawn = run_cli("build", cwd=first, env={"MJCFBUILD_CACHE_DIR": str(cache)})
    assert drawn.code == EXIT_OK and "previews (" in drawn.stdout, drawn.stdout + drawn.stderr
    assert not re.search(r"\] (previews|reference kinematics) .*from cache", drawn.stdout)

    env = {"MJCFBUILD_CACHE_DIR": str(cache), VARIABLE: "previews-draw:raise"}
    second = copy_example("arm", tmp_path / "second")
    taken = run_cli("build", cwd=second, env=env)
    assert taken.code == EXIT_OK, taken.stdout + taken.stderr
    assert re.search(r"\] previews \(\d+\.\d+ s, from cache\)", taken.stdout), taken.stdout
    assert re.search(r"\] reference kinematics \(\d+\.\d+ s, from cache\)", taken.stdout)
    assert "no preview pictures" not in (second / "mjcf/report/report.md").read_text()
    assert _pictures(second) == _pictures(first) and len(_pictures(first)) >= 4
    for name in (".mjcfbuild/previews.json", ".mjcfbuild/reference.json"):
        assert (second / "mjcf" / name).read_bytes() == (first / "mjcf" / name).read_bytes()

    for picture in cache.rglob("picture.png"):
        picture.write_bytes(b"not the picture that was stored")
    third = copy_example("arm", tmp_path / "third")
    redrawn = run_cli("build", "-q", cwd=third, env=env)
    assert redrawn.code == EXIT_OK, redrawn.stdout + redrawn.stderr
    report = (third / "mjcf/report/report.md").read_text()
    assert "drawing them failed with RuntimeError: failpoint previews-draw" in report


def test_pictures_that_cannot_be_drawn_again_are_not_left_behind(arm, tmp_path):
    """A scene that no longer loads draws no pictures: the earlier build's must not stay in
    the report folder, nor in report.md, as a clean build of the same folder has none."""
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    built = run_cli("build", "-q", cwd=arm, env=env)
    assert built.code == EXIT_OK, built.stdout + built.stderr
    previews = arm / "mjcf/report/previews"
    assert len(list(previews.glob("*.png"))) >= 4

    (arm / "myscene.xml").write_text(
        '<mujoco><include file="example_arm.xml"/>'
        '<asset><texture name="grid" type="2d" file="missing.png"/>'
        '<material name="grid" texture="grid"/></asset>'
        '<worldbody><light pos="0 0 3"/>'
        '<geom type="plane" size="2 2 0.1" material="grid"/></worldbody></mujoco>'
    )
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "scene:\n  file: myscene.xml\n")
    failed = run_cli("build", "-q", cwd=arm, env=env)
    assert failed.code != EXIT_OK and "does not load" in failed.stderr, failed.stderr
    assert not previews.exists()
    assert not (arm / "mjcf/.mjcfbuild/previews.json").exists()
    assert "## Previews" not in (arm / "mjcf/report/report.md").read_text()


def test_pictures_no_longer_asked_for_are_not_left_behind(arm, tmp_path):
    """check.previews: false after a build that drew them: the pictures go, as the training
    variant's files do when it is no longer asked for."""
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    assert run_cli("build", "-q", cwd=arm, env=env).code == EXIT_OK
    previews = arm / "mjcf/report/previews"
    assert len(list(previews.glob("*.png"))) >= 4

    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "check:\n  previews: false\n")
    rebuilt = run_cli("build", "-q", cwd=arm, env=env)
    assert rebuilt.code == EXIT_OK, rebuilt.stdout + rebuilt.stderr
    assert not previews.exists()
    assert not (arm / "mjcf/.mjcfbuild/previews.json").exists()
    assert "## Previews" not in (arm / "mjcf/report/report.md").read_text()


def test_a_picture_of_the_user_s_in_the_previews_folder_stays(arm, tmp_path):
    """Pictures no longer asked for go only where the step's record says it wrote those bytes:
    a picture the user put in the folder is theirs."""
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    assert run_cli("build", "-q", cwd=arm, env=env).code == EXIT_OK
    mine = arm / "mjcf/report/previews/annotated.png"
    mine.write_bytes(b"\x89PNG mine")
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "check:\n  previews: false\n")
    assert run_cli("build", "-q", cwd=arm, env=env).code == EXIT_OK
    assert mine.read_bytes() == b"\x89PNG mine"
    assert sorted(p.name for p in mine.parent.iterdir()) == ["annotated.png"]
