"""The training variant's files go when robot.yaml stops asking for them, and the model of an
old name when it is renamed (real builds)."""

from __future__ import annotations

import pytest

import mjcfbuild
from mjcfbuild.errors import BuildFailed
from tests.conftest import copy_example, run_cli


def build(folder):
    return mjcfbuild.build(folder / "robot.yaml", jobs=1, check=False)


def built_with_training(tmp_path):
    """The example arm built with the variant: its folder, manifest and manifest text without
    the training line."""
    folder = copy_example("arm", tmp_path)
    manifest = folder / "robot.yaml"
    plain = manifest.read_text()
    manifest.write_text(plain + "  training: true\n")
    build(folder)
    return folder, manifest, plain


def test_turning_training_off_removes_the_variant_and_its_scene(tmp_path):
    folder, manifest, plain = built_with_training(tmp_path)
    out = folder / "mjcf"
    variant, scene = sorted(out.glob("*_mjx.xml"))
    assert variant.name != "scene_mjx.xml" and scene.name == "scene_mjx.xml"
    (out / "notes_mjx.xml").write_text("<mujoco/>")  # the user's: no build wrote it
    manifest.write_text(plain)
    build(folder)
    assert not variant.exists() and not scene.exists()
    assert not (out / ".mjcfbuild" / "training.json").exists()
    assert (out / "notes_mjx.xml").exists() and (out / "scene.xml").exists()
    report = (out / "report" / "report.md").read_text()
    assert "## Training variant" not in report
    # On again: the variant is back (its task's outputs are missing, so it reruns).
    manifest.write_text(plain + "  training: true\n")
    assert "training" in build(folder).ran
    assert variant.exists() and scene.exists()


def test_a_new_name_for_the_variant_removes_the_old_files(tmp_path):
    folder, manifest, plain = built_with_training(tmp_path)
    out = folder / "mjcf"
    old = sorted(out.glob("*_mjx.xml"))
    manifest.write_text(
        plain + "  training:\n    file: trainer.xml\n    scene: trainer_scene.xml\n"
    )
    build(folder)
    assert not any(path.exists() for path in old)
    assert (out / "trainer.xml").exists() and (out / "trainer_scene.xml").exists()


def test_a_renamed_robot_leaves_no_old_model_behind(tmp_path):
    """name: changed: the old model went on looking current beside the new one."""
    folder = copy_example("arm", tmp_path)
    build(folder)
    out = folder / "mjcf"
    old = out / "example_arm.xml"
    assert old.exists()
    (out / "mine.xml").write_text("<mujoco/>")  # the user's: no build wrote it
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("name: example_arm", "name: arm2"))
    build(folder)
    assert (out / "arm2.xml").exists() and (out / "scene.xml").exists()
    assert not old.exists() and (out / "mine.xml").exists()
    # One the user edited stays, as clean keeps it.
    manifest.write_text(manifest.read_text().replace("name: arm2", "name: arm3"))
    edited = out / "arm2.xml"
    edited.write_text(edited.read_text() + "<!-- mine -->\n")
    build(folder)
    assert edited.exists() and (out / "arm3.xml").exists()
    # A build that fails under the new name leaves the old model: there is no other yet.
    manifest.write_text(manifest.read_text().replace("name: arm3", "name: arm4"))
    (folder / "meshes" / "forearm.obj").write_text("not a mesh\n")
    with pytest.raises(BuildFailed):
        build(folder)
    assert (out / "arm3.xml").exists() and not (out / "arm4.xml").exists()


def test_the_build_says_which_old_files_it_removed(tmp_path):
    folder = copy_example("arm", tmp_path)
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("name: example_arm", "name: arm2"))
    renamed = run_cli("build", "--no-check", cwd=folder)
    assert renamed.code == 0, renamed.stderr
    assert (
        "mjcfbuild: removed mjcf/example_arm.xml: the model's files under names robot.yaml no "
        "longer gives (now mjcf/arm2.xml, mjcf/scene.xml)"
    ) in renamed.stdout.splitlines()
    manifest.write_text(manifest.read_text().replace("name: arm2", "name: arm3"))
    quiet = run_cli("build", "--no-check", "-q", cwd=folder)
    assert quiet.code == 0 and quiet.stdout == "", quiet.stdout


def test_a_model_edited_before_a_rename_is_named_and_protected_when_the_name_returns(tmp_path):
    """Renamed and back: the assembly that wrote the new name passed for the old name's (its
    file was there, edited), 'model ready' named the edit, and the next change wrote over it."""
    folder = copy_example("arm", tmp_path)
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    model = folder / "mjcf" / "example_arm.xml"
    model.write_text(model.read_text() + "<!-- tuned -->\n")
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("name: example_arm", "name: arm2"))
    renamed = run_cli("build", "--no-check", cwd=folder)
    assert renamed.code == 0, renamed.stderr
    assert "mjcfbuild: kept mjcf/example_arm.xml: edited since a build wrote it" in renamed.stdout
    manifest.write_text(manifest.read_text().replace("name: arm2", "name: example_arm"))
    back = run_cli("build", "--no-check", cwd=folder)
    assert back.code == 7 and "mjcf/example_arm.xml: was edited" in back.stderr, back.stderr
    assert model.read_text().endswith("<!-- tuned -->\n")
