"""``mjcfbuild clean``: everything a build wrote goes, and nothing else."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

from mjcfbuild.errors import EXIT_OUTPUT
from mjcfbuild.failpoints import VARIABLE
from tests.conftest import ROOT, run_cli


def test_clean_removes_outputs_and_state_and_keeps_other_files(arm):
    assert run_cli("build", "-q", cwd=arm).code == 0
    keep = arm / "mjcf" / "NOTES.md"
    keep.write_text("my notes\n")
    result = run_cli("clean", cwd=arm)
    assert result.code == 0
    assert result.stdout.startswith("mjcfbuild: removed mjcf/example_arm.xml, mjcf/scene.xml")
    assert sorted(p.name for p in (arm / "mjcf").iterdir()) == ["NOTES.md"]
    again = run_cli("build", "-q", cwd=arm)
    assert again.code == 0 and (arm / "mjcf" / "example_arm.xml").exists()


def test_clean_with_nothing_built(arm):
    result = run_cli("clean", cwd=arm)
    assert result.code == 0 and result.stdout.strip() == "mjcfbuild: removed nothing"


def test_the_manifest_is_a_positional_argument(built_arm, tmp_path):
    arm = built_arm
    result = run_cli("clean", str(arm / "robot.yaml"), cwd=tmp_path)
    assert result.code == 0, result.stderr
    assert not (arm / "mjcf").exists()


def test_quiet_before_or_after_the_command_prints_nothing(arm):
    for argv in (["-q", "clean"], ["clean", "-q"]):
        assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
        result = run_cli(*argv, cwd=arm)
        assert result.code == 0 and result.stdout == "", result.stdout
        assert not (arm / "mjcf").exists()


def _output_setting(arm, text: str) -> None:
    """Replace the arm's ``output:`` section with ``text``."""
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("output:\n  folder: mjcf\n", text))


def _files_below(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if not p.is_dir())


def test_files_the_user_put_among_the_outputs_stay(built_arm):
    arm = built_arm
    out = arm / "mjcf"
    (out / "assets" / "my_texture.png").write_bytes(b"my own picture")
    (out / "report" / "notes.md").write_text("my notes\n")
    result = run_cli("clean", cwd=arm)
    assert result.code == 0, result.stderr
    assert _files_below(out) == ["assets/my_texture.png", "report/notes.md"]
    assert (out / "assets" / "my_texture.png").read_bytes() == b"my own picture"
    # The folders stay, with the user's files: the line does not say they went. Before:
    # "removed ... mjcf/assets/ (5 files)", as for a folder removed with its files.
    assert "5 files in mjcf/assets/" in result.stdout
    assert "mjcf/assets/ (5 files)" not in result.stdout
    assert "kept mjcf/assets/my_texture.png, mjcf/report/notes.md" in result.stdout


def test_the_removal_line_says_what_of_the_state_folder_stays_and_why(built_arm):
    arm = built_arm
    scene = arm / "mjcf" / "scene.xml"
    scene.write_text(scene.read_text() + "<!-- my edit -->\n")
    result = run_cli("clean", cwd=arm)
    assert result.code == 0, result.stderr
    first = result.stdout.splitlines()[0]
    assert first.endswith(
        "the build state in mjcf/.mjcfbuild/ (but for foreign.json, which records the edited "
        "file kept as yours, so that no build writes over it)"
    ), first
    assert (arm / "mjcf" / ".mjcfbuild" / "foreign.json").is_file()
    assert "mjcfbuild: kept mjcf/scene.xml (edited since mjcfbuild wrote it)" in result.stdout


def test_an_output_folder_up_a_level_keeps_the_parents_own_files(arm):
    # The case: with output.folder: .. the parent's own assets/ was deleted.
    parent = arm.parent
    (parent / "assets").mkdir()
    (parent / "assets" / "logo.png").write_bytes(b"the parent's")
    _output_setting(arm, "output:\n  folder: ..\n  allow_outside: true\n")
    before = _files_below(parent)
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert (parent / "assets" / "base.obj").is_file()
    result = run_cli("clean", cwd=arm)
    assert result.code == 0, result.stderr
    assert _files_below(parent) == before
    assert (parent / "assets" / "logo.png").read_bytes() == b"the parent's"


def test_clean_of_the_description_s_own_folder_names_only_files_left_among_outputs(arm):
    """output.folder: . - the kept line listed the description (and .git's files)."""
    _output_setting(arm, "output:\n  folder: .\n")
    (arm / ".git").mkdir()
    (arm / ".git" / "HEAD").write_text("ref: refs/heads/main\n")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    (arm / "assets" / "logo.png").write_bytes(b"mine")
    result = run_cli("clean", cwd=arm)
    assert result.code == 0, result.stderr
    kept = [line for line in result.stdout.splitlines() if line.startswith("mjcfbuild: kept")]
    assert kept == ["mjcfbuild: kept assets/logo.png (not written by mjcfbuild)"], kept
    assert (arm / "robot.yaml").exists() and (arm / ".git" / "HEAD").exists()


def test_a_dry_run_lists_what_would_go_and_removes_nothing(built_arm):
    arm = built_arm
    (arm / "mjcf" / "NOTES.md").write_text("mine\n")
    before = _files_below(arm / "mjcf")
    result = run_cli("clean", "--dry-run", cwd=arm)
    assert result.code == 0, result.stderr
    assert _files_below(arm / "mjcf") == before
    listed = result.stdout.splitlines()
    assert listed[0] == "mjcfbuild: would remove:"
    assert "  mjcf/assets/base.obj" in listed and "  mjcf/example_arm.xml" in listed
    assert "  mjcf/.mjcfbuild/" in listed
    assert not any("NOTES.md" in line for line in listed[:-1])
    assert listed[-1] == "mjcfbuild: kept mjcf/NOTES.md (not written by mjcfbuild)"
    # what it listed is what clean removes
    assert run_cli("clean", cwd=arm).code == 0
    assert _files_below(arm / "mjcf") == ["NOTES.md"]


def test_every_optional_output_goes_but_the_package_changelog(arm):
    _output_setting(
        arm, "output:\n  folder: mjcf\n  package: true\n  urdf: exported.urdf\n  training: true\n"
    )
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert (arm / "mjcf" / "package" / "CHANGELOG.md").is_file()
    assert (arm / "mjcf" / "example_arm_mjx.xml").is_file()
    assert run_cli("clean", "-q", cwd=arm).code == 0
    # but the package's changelog, a history no build can write again
    assert _files_below(arm / "mjcf") == ["package/CHANGELOG.md"]


def test_the_changelog_with_a_note_a_rebuild_kept_is_not_removed(arm):
    """A rebuild keeps the user's note below its new entry and records the file as written:
    clean must not take the history, and the note, for a file it can write again."""
    _output_setting(arm, "output:\n  folder: mjcf\n  package: true\n")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    changelog = arm / "mjcf" / "package" / "CHANGELOG.md"
    changelog.write_text(changelog.read_text() + "\n- my own note\n")
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("elbow: 1.2", "elbow: 1.0"))
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert "- my own note" in changelog.read_text()
    result = run_cli("clean", cwd=arm)
    assert result.code == 0, result.stderr
    assert (
        "mjcfbuild: kept mjcf/package/CHANGELOG.md (the history of earlier builds: no build can "
        "write it again; remove it yourself if it is to go)"
    ) in result.stdout.splitlines()
    assert "- my own note" in changelog.read_text()


def test_a_link_put_in_place_of_an_output_is_not_followed(built_arm, tmp_path):
    arm = built_arm
    mine = tmp_path / "my_scene.xml"
    mine.write_text("<mujoco/>")
    scene = arm / "mjcf" / "scene.xml"
    scene.unlink()
    scene.symlink_to(mine)
    result = run_cli("clean", cwd=arm)
    assert result.code == 0, result.stderr
    assert scene.is_symlink() and mine.read_text() == "<mujoco/>"
    assert "kept mjcf/scene.xml" in result.stdout


def test_a_linked_assets_folder_is_refused_and_nothing_outside_goes(built_arm, tmp_path):
    arm = built_arm
    elsewhere = tmp_path / "elsewhere"
    shutil.copytree(arm / "mjcf" / "assets", elsewhere)
    shutil.rmtree(arm / "mjcf" / "assets")
    (arm / "mjcf" / "assets").symlink_to(elsewhere)
    result = run_cli("clean", cwd=arm)
    assert result.code == EXIT_OUTPUT
    assert result.stderr.startswith("mjcfbuild: error: mjcf/assets: is a symbolic link")
    assert len(result.stderr.splitlines()) == 1 and "Traceback" not in result.stderr
    assert (elsewhere / "base.obj").is_file() and (arm / "mjcf" / "example_arm.xml").is_file()


def test_a_folder_built_without_a_record_is_left_with_a_warning(built_arm):
    arm = built_arm
    (arm / "mjcf" / ".mjcfbuild" / "written.json").unlink()
    before = _files_below(arm / "mjcf")
    result = run_cli("clean", cwd=arm)
    assert result.code == 0
    assert "no record of the files builds wrote here" in result.stderr
    assert _files_below(arm / "mjcf") == before


def test_the_state_folder_goes_while_clean_still_holds_the_lock(built_arm):
    """A real clean, stopped where it still holds the lock: the state folder is gone already,
    so a build that takes the lock after it keeps the state folder it makes."""
    arm = built_arm
    cleaning = subprocess.Popen(
        [sys.executable, "-m", "mjcfbuild", "clean"],
        cwd=arm,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "PYTHONPATH": str(ROOT), VARIABLE: "clean-removed:stop"},
    )
    try:
        _, status = os.waitpid(cleaning.pid, os.WUNTRACED)
        assert os.WIFSTOPPED(status), status
        held = [os.readlink(fd) for fd in Path(f"/proc/{cleaning.pid}/fd").iterdir()]
        assert any(link.endswith("/mjcf/.mjcfbuild/lock (deleted)") for link in held), held
        assert not (arm / "mjcf").exists()  # before: .mjcfbuild/ went after the lock
        built = run_cli("build", "-q", "--no-check", "--timeout", "60", cwd=arm)
        assert built.code == 0, built.stderr
    finally:
        os.kill(cleaning.pid, signal.SIGCONT)
    _, errors = cleaning.communicate(timeout=60)
    assert cleaning.returncode == 0, errors
    # What the build made after clean had removed everything stays: nothing to redo.
    assert (arm / "mjcf" / ".mjcfbuild" / "lock").exists()
    again = run_cli("build", "--no-check", cwd=arm)
    assert again.code == 0 and " 0 run," in again.stdout, again.stdout


def test_a_file_the_build_wrote_and_the_user_edited_stays_and_is_named(arm):
    _output_setting(arm, "output:\n  folder: mjcf\n  package: true\n")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    changelog = arm / "mjcf" / "package" / "CHANGELOG.md"
    changelog.write_text(changelog.read_text() + "\n- my own note\n")
    kept = "mjcfbuild: kept mjcf/package/CHANGELOG.md (edited since mjcfbuild wrote it)"
    dry = run_cli("clean", "-n", cwd=arm)
    assert dry.code == 0, dry.stderr
    assert kept in dry.stdout.splitlines(), dry.stdout
    assert "  mjcf/package/CHANGELOG.md" not in dry.stdout.splitlines()
    result = run_cli("clean", cwd=arm)
    assert result.code == 0, result.stderr
    assert kept in result.stdout.splitlines()
    assert _files_below(arm / "mjcf") == ["package/CHANGELOG.md"]
    assert changelog.read_text().endswith("- my own note\n")


def test_the_record_drops_files_that_are_gone_and_hashes_what_was_written(arm):
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    record = arm / "mjcf" / ".mjcfbuild" / "written.json"
    files = json.loads(record.read_text())["files"]
    assert (
        files["example_arm.xml"]
        == hashlib.md5((arm / "mjcf" / "example_arm.xml").read_bytes()).hexdigest()
    )
    # An entry an earlier build left of a file that is gone (a mesh renamed since).
    files["assets/renamed_long_ago.obj"] = "0" * 32
    record.write_text(json.dumps({"files": files}))
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert "assets/renamed_long_ago.obj" not in json.loads(record.read_text())["files"]


def test_quiet_dry_run_still_lists_what_would_be_removed(built_arm):
    (built_arm / "mjcf" / "NOTES.md").write_text("my notes\n")
    listed = run_cli("clean", "-n", cwd=built_arm)
    assert listed.code == 0, listed.stderr
    assert "kept mjcf/NOTES.md" in listed.stdout
    for argv in (["clean", "-n", "-q"], ["-q", "clean", "--dry-run"]):
        quiet = run_cli(*argv, cwd=built_arm)
        assert quiet.code == 0, quiet.stderr
        lines = quiet.stdout.splitlines()
        assert lines[0] == "mjcfbuild: would remove:" and "  mjcf/.mjcfbuild/" in lines
        assert lines == [line for line in listed.stdout.splitlines() if "kept" not in line]
    assert (built_arm / "mjcf" / "scene.xml").exists()


def test_an_edited_model_clean_kept_is_not_written_over_by_the_next_build(arm):
    """With no record left, a folder holding a model with mjcfbuild's header was taken for a
    fresh clone's committed outputs, and the next build wrote over the edit clean had kept."""
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    model = arm / "mjcf" / "example_arm.xml"
    model.write_text(model.read_text() + "<!-- mine -->\n")
    result = run_cli("clean", cwd=arm)
    assert (
        "mjcfbuild: kept mjcf/example_arm.xml (edited since mjcfbuild wrote it)"
        in result.stdout.splitlines()
    )
    # The record stays out of git, as the state folder always does.
    state = arm / "mjcf" / ".mjcfbuild"
    assert sorted(path.name for path in state.iterdir()) == [".gitignore", "foreign.json"]
    again = run_cli("build", "-q", "--no-check", cwd=arm)
    assert again.code == 7, again.stderr
    assert again.stderr.startswith(
        "mjcfbuild: error: mjcf/example_arm.xml: was edited since a build wrote it"
    )
    assert model.read_text().endswith("<!-- mine -->\n")
    model.unlink()  # moved away: the build writes its own
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0


def test_after_clean_kept_an_edit_the_next_build_still_finds_the_users_files(arm):
    """The .gitignore clean leaves beside its record made the next build take the folder for
    one an older mjcfbuild built, and write over a scene.xml the user had put there."""
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    model = arm / "mjcf" / "example_arm.xml"
    model.write_text(model.read_text() + "<!-- mine -->\n")
    assert run_cli("clean", "-q", cwd=arm).code == 0
    model.unlink()
    scene = arm / "mjcf" / "scene.xml"
    scene.write_text("<mujoco><!-- my scene --></mujoco>\n")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == 7 and "mjcf/scene.xml: is not mjcfbuild's" in result.stderr
    assert "my scene" in scene.read_text()
