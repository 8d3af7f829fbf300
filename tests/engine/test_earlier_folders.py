"""A robot.yaml whose output.folder changed leaves no stale model in the old folder, and keeps
the user's files there (real builds)."""

from __future__ import annotations

import subprocess

import mjcfbuild
from tests.conftest import copy_example, run_cli


def build(folder):
    return mjcfbuild.build(folder / "robot.yaml", jobs=1, check=False)


def move_output(folder, old, new):
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace(f"  folder: {old}\n", f"  folder: {new}\n"))


def test_the_old_folder_loses_the_builds_files_and_keeps_the_users(tmp_path):
    folder = copy_example("arm", tmp_path)
    build(folder)
    old = folder / "mjcf"
    (old / "NOTES.md").write_text("mine\n")  # no build wrote it
    scene = old / "scene.xml"
    scene.write_text(scene.read_text() + "<!-- tuned -->\n")  # an edit of the build's file
    move_output(folder, "mjcf", "models")
    build(folder)
    assert (folder / "models" / "example_arm.xml").exists()
    left = sorted(str(p.relative_to(old)) for p in old.rglob("*") if ".mjcfbuild" not in p.parts)
    assert left == ["NOTES.md", "scene.xml"], left  # no model, assets or report
    # The edit stays recorded as the user's (as clean leaves it); nothing else of the state.
    assert sorted(p.name for p in (old / ".mjcfbuild").iterdir()) == [".gitignore", "foreign.json"]
    # Moved back: the folder is the output folder again, and models/ goes whole.
    move_output(folder, "models", "mjcf")
    (old / "scene.xml").unlink()
    build(folder)
    assert not (folder / "models").exists()
    assert (old / "example_arm.xml").exists() and (old / "NOTES.md").exists()


def test_another_robot_yaml_s_folder_and_a_folder_above_stay(tmp_path):
    """Only folders recording this robot.yaml are emptied; robot.yaml's own folder (the
    output folder was '.') loses the build's files, never the description."""
    folder = copy_example("arm", tmp_path)
    second = folder / "second.yaml"
    second.write_text(
        (folder / "robot.yaml").read_text().replace("  folder: mjcf\n", "  folder: other\n")
    )
    mjcfbuild.build(second, jobs=1, check=False)
    move_output(folder, "mjcf", ".")
    build(folder)
    assert (folder / "example_arm.xml").exists()
    move_output(folder, ".", "models")
    build(folder)
    assert not (folder / "example_arm.xml").exists() and not (folder / "scene.xml").exists()
    assert not (folder / ".mjcfbuild").exists()
    for kept in ("robot.yaml", "urdf", "meshes", "package.xml", "config"):
        assert (folder / kept).exists(), kept
    assert (folder / "other" / "example_arm.xml").exists()  # second.yaml's


def test_the_build_says_so_and_the_commit_hook_asks_for_the_removal(tmp_path):
    folder = copy_example("arm", tmp_path)

    def git(*args):
        subprocess.run(["git", *args], cwd=folder, check=True, capture_output=True)

    git("init", "-q")
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    (folder / "mjcf" / "NOTES.md").write_text("mine\n")
    git("add", "-A")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "built")
    move_output(folder, "mjcf", "models")
    moved = run_cli("build", "--no-check", "--fail-on-change", cwd=folder)
    assert moved.code == 6, moved.stderr
    assert (
        "mjcfbuild: removed 10 files a build wrote in mjcf/, robot.yaml's output folder before "
        "(now models/); kept mjcf/NOTES.md (not written by a build, or edited since)"
    ) in moved.stdout.splitlines(), moved.stdout
    assert "files were removed that git still has: mjcf/example_arm.xml" in moved.stderr
    assert "mjcf/assets/" in moved.stderr  # in a folder the build removed too
    git("add", "-A")
    assert run_cli("build", "--no-check", "--fail-on-change", cwd=folder).code == 0


def test_an_edit_kept_in_the_old_folder_stops_a_build_that_returns_to_it(tmp_path):
    folder = copy_example("arm", tmp_path)
    build(folder)
    model = folder / "mjcf" / "example_arm.xml"
    model.write_text(model.read_text() + "<!-- tuned -->\n")
    move_output(folder, "mjcf", "models")
    build(folder)
    move_output(folder, "models", "mjcf")
    back = run_cli("build", "--no-check", cwd=folder)
    assert back.code == 7 and "mjcf/example_arm.xml: was edited" in back.stderr, back.stderr
    assert model.read_text().endswith("<!-- tuned -->\n")


def test_a_copy_or_a_move_of_an_output_folder_is_never_emptied(tmp_path):
    """A snapshot (cp -r) of the output folder, or the folder moved aside (mv), recorded the
    same robot.yaml: the next build emptied and removed it as an 'earlier output folder'."""
    import shutil

    folder = copy_example("arm", tmp_path)
    build(folder)
    out = folder / "mjcf"
    shutil.copytree(out, folder / "snapshot")
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("elbow: 1.2", "elbow: 1.1"))
    build(folder)
    assert (folder / "snapshot" / "example_arm.xml").exists()
    out.rename(folder / "mjcf_old")
    manifest.write_text(manifest.read_text().replace("elbow: 1.1", "elbow: 1.0"))
    build(folder)
    assert (folder / "mjcf_old" / "example_arm.xml").exists()
    assert (folder / "mjcf" / "example_arm.xml").exists()
