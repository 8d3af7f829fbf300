"""The output folder's guard: inside robot.yaml's folder tree unless allowed, never through a
link. Every refusal comes before anything is written."""

from __future__ import annotations

import re

from mjcfbuild.errors import EXIT_MANIFEST, EXIT_OUTPUT
from tests.cli.error_catalogue import urdf
from tests.conftest import run_cli


def _output_folder(arm, value: str, extra: str = "") -> None:
    manifest = arm / "robot.yaml"
    text = manifest.read_text().replace("  folder: mjcf\n", f"  folder: {value}\n{extra}")
    manifest.write_text(text)


def _output_line(arm) -> int:
    lines = (arm / "robot.yaml").read_text().splitlines()
    return next(i for i, line in enumerate(lines, 1) if line.startswith("  folder:"))


def _refused(result, arm) -> str:
    assert result.code == EXIT_OUTPUT, result.stderr
    assert "Traceback" not in result.stderr and len(result.stderr.splitlines()) == 1
    assert result.stderr.startswith(f"mjcfbuild: error: robot.yaml:{_output_line(arm)}:")
    return result.stderr


def test_the_filesystem_root_is_refused(arm):
    _output_folder(arm, "/")
    stderr = _refused(run_cli("build", "-q", "--no-check", cwd=arm), arm)
    assert "output.folder: '/' is outside" in stderr
    assert "output.allow_outside: true" in stderr and "--allow-outside" in stderr
    _refused(run_cli("build", "--dry-run", cwd=arm), arm)  # says what the build would say


def test_a_folder_up_the_tree_is_refused_and_nothing_is_written(arm):
    _output_folder(arm, "../out")
    stderr = _refused(run_cli("build", "-q", "--no-check", cwd=arm), arm)
    assert f"'../out' ({arm.parent / 'out'}) is outside {arm}" in stderr
    assert not (arm.parent / "out").exists()
    _refused(run_cli("clean", cwd=arm), arm)


def test_the_setting_or_the_flag_allows_it(arm):
    _output_folder(arm, "../out")
    assert run_cli("build", "-q", "--no-check", "--allow-outside", cwd=arm).code == 0
    assert (arm.parent / "out" / "example_arm.xml").is_file()
    assert run_cli("clean", "-q", "--allow-outside", cwd=arm).code == 0
    assert not (arm.parent / "out").exists()
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("../out\n", "../out\n  allow_outside: true\n"))
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert (arm.parent / "out" / "example_arm.xml").is_file()


def test_a_linked_output_folder_is_resolved(arm, tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (arm / "mjcf").symlink_to(elsewhere)
    stderr = _refused(run_cli("build", "-q", "--no-check", cwd=arm), arm)
    assert f"'mjcf' leads through a link to {elsewhere}" in stderr
    assert list(elsewhere.iterdir()) == []
    # a link that stays inside the tree is the user's layout, not an escape
    (arm / "mjcf").unlink()
    (arm / "build").mkdir()
    (arm / "mjcf").symlink_to(arm / "build")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert (arm / "build" / "example_arm.xml").is_file()
    result = run_cli("clean", "-q", cwd=arm)
    assert result.code == 0, result.stderr
    assert (arm / "mjcf").is_symlink() and list((arm / "build").iterdir()) == []


def test_a_linked_assets_folder_is_not_written_through_even_when_allowed(arm, tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (arm / "mjcf").mkdir()
    (arm / "mjcf" / "assets").symlink_to(elsewhere)
    _output_folder(arm, "mjcf", "  allow_outside: true\n")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT and len(result.stderr.splitlines()) == 1
    assert result.stderr.startswith(
        f"mjcfbuild: error: mjcf/assets: is a symbolic link (to {elsewhere})"
    )
    assert list(elsewhere.iterdir()) == [] and not (arm / "mjcf" / ".mjcfbuild").exists()


def test_a_linked_report_subfolder_an_earlier_build_wrote_is_refused(arm, tmp_path):
    assert run_cli("build", "-q", cwd=arm).code == 0  # the check writes report/tuning/
    tuning = arm / "mjcf" / "report" / "tuning"
    assert tuning.is_dir()  # a folder no fixed list names: the record does
    elsewhere = tmp_path / "elsewhere"
    tuning.rename(elsewhere)
    tuning.symlink_to(elsewhere)
    (arm / "robot.yaml").write_text((arm / "robot.yaml").read_text() + "# edited\n")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT
    assert "mjcf/report/tuning: is a symbolic link" in result.stderr


def test_check_refuses_a_folder_linked_after_the_build(arm, tmp_path):
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    report = arm / "mjcf" / "report"
    elsewhere = tmp_path / "elsewhere"
    report.rename(elsewhere)
    report.symlink_to(elsewhere)
    before = sorted(p.name for p in elsewhere.iterdir())
    result = run_cli("check", cwd=arm)
    assert result.code == EXIT_OUTPUT and len(result.stderr.splitlines()) == 1, result.stderr
    assert result.stderr.startswith("mjcfbuild: error: mjcf/report: is a symbolic link")
    assert sorted(p.name for p in elsewhere.iterdir()) == before


def _refused_as_input(result, line: int, field: str, file: str, what: str) -> None:
    assert result.code == EXIT_MANIFEST, result.stdout + result.stderr
    assert "Traceback" not in result.stderr and len(result.stderr.splitlines()) == 1
    assert result.stderr.startswith(
        f"mjcfbuild: error: robot.yaml:{line}:3: {field}: would write {file}, "
        f"which the build reads ({what})"
    ), result.stderr


def test_an_exported_urdf_over_the_source_urdf_is_refused(tmp_path):
    source = tmp_path / "robot.urdf"
    source.write_text(urdf())
    (tmp_path / "robot.yaml").write_text(
        "name: robot\nsource:\n  urdf: robot.urdf\noutput:\n  folder: .\n  urdf: robot.urdf\n"
    )
    result = run_cli("build", "-q", "--no-check", cwd=tmp_path)
    _refused_as_input(result, 6, "output.urdf", "robot.urdf", "the source or a file it includes")
    assert source.read_text() == urdf()
    assert not (tmp_path / "robot.xml").exists()


def test_an_output_over_a_file_xacro_includes_is_refused(arm):
    _output_folder(arm, "urdf", "  urdf: finger.xacro\n")
    include = (arm / "urdf" / "finger.xacro").read_bytes()
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    line = _output_line(arm) + 1
    _refused_as_input(
        result, line, "output.urdf", "urdf/finger.xacro", "the source or a file it includes"
    )
    assert (arm / "urdf" / "finger.xacro").read_bytes() == include


def test_a_folder_the_build_fills_that_holds_meshes_is_refused(arm):
    _output_folder(arm, ".", "  urdf: {file: exported.urdf, meshes: meshes}\n")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_MANIFEST, result.stdout + result.stderr
    assert result.stderr.startswith(
        f"mjcfbuild: error: robot.yaml:{_output_line(arm) + 1}:3: output.urdf: would write "
        "into meshes/, which holds meshes/upper_arm.dae, a file the build reads (a mesh or a "
        "file it references)"
    ), result.stderr


def test_the_model_over_the_mujoco_inputs_file_is_refused(arm):
    (arm / "extra.xml").write_text("<mujoco_inputs/>\n")
    _output_folder(arm, ".", "  robot: extra.xml\n")
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "mujoco_inputs:\n  file: extra.xml\n")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    _refused_as_input(
        result, _output_line(arm) + 1, "output.robot", "extra.xml", "the mujoco_inputs file"
    )
    assert (arm / "extra.xml").read_text() == "<mujoco_inputs/>\n"


def test_a_second_robot_yaml_may_not_build_into_the_folder_of_another(arm):
    """Two manifests with one output folder deleted each other's assets and rewrote each
    other's scene and report, exit 0, and clean of one listed the other's model."""
    (arm / "other.yaml").write_text(
        (arm / "robot.yaml").read_text().replace("name: example_arm", "name: other_arm")
    )
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    model = (arm / "mjcf" / "example_arm.xml").read_bytes()
    line = _output_line(arm)
    for command in (["build", "other.yaml", "-q", "--no-check"], ["clean", "-n", "other.yaml"]):
        result = run_cli(*command, cwd=arm)
        assert result.code == EXIT_MANIFEST, result.stderr
        assert result.stderr.startswith(
            f"mjcfbuild: error: other.yaml:{line}:3: output.folder: 'mjcf' is the output "
            "folder of robot.yaml, which built there; two robot.yaml files cannot share one"
        ), result.stderr
    assert not (arm / "mjcf" / "other_arm.xml").exists()
    assert (arm / "mjcf" / "example_arm.xml").read_bytes() == model
    # A manifest renamed (or removed) gives its folder up.
    (arm / "robot.yaml").rename(arm / "before.yaml")
    assert run_cli("build", "other.yaml", "-q", "--no-check", cwd=arm).code == 0
    assert run_cli("build", "before.yaml", "-q", "--no-check", cwd=arm).code == EXIT_MANIFEST


def test_a_file_of_the_users_in_the_output_folder_is_never_written_over(arm):
    """A scene.xml and an asset put in the folder before the first build were replaced
    without a word; so was an asset ``clean`` had kept as the user's, once a mesh of its
    name came to the build."""
    assets = arm / "mjcf" / "assets"
    assets.mkdir(parents=True)
    (arm / "mjcf" / "scene.xml").write_text("<mujoco/>\n")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    assert result.stderr.startswith(
        "mjcfbuild: error: mjcf/scene.xml: is not mjcfbuild's (it was in the output folder "
        "before the build, and no build wrote it); a build never writes over a file of yours"
    ), result.stderr
    assert (arm / "mjcf" / "scene.xml").read_text() == "<mujoco/>\n"
    (arm / "mjcf" / "scene.xml").unlink()
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    # After a build: the user's file beside its assets, then a mesh of that name.
    (assets / "wrist.obj").write_text("# mine\n")
    mesh = arm / "meshes" / "wrist.stl"
    mesh.write_bytes((arm / "meshes" / "base.stl").read_bytes())
    urdf = arm / "urdf" / "arm.urdf.xacro"
    urdf.write_text(urdf.read_text().replace("meshes/base.stl", "meshes/wrist.stl"))
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    assert result.stderr.startswith("mjcfbuild: error: mjcf/assets/wrist.obj: is not"), (
        result.stderr
    )
    assert (assets / "wrist.obj").read_text() == "# mine\n"
    (assets / "wrist.obj").unlink()
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0


def test_a_report_clean_kept_as_edited_is_not_written_over(arm):
    """clean keeps an edited report.md as the user's; the report, written by the engine and
    not by a step, wrote over it all the same."""
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    report = arm / "mjcf" / "report" / "report.md"
    report.write_text(report.read_text() + "MY NOTES\n")
    assert run_cli("clean", "-q", cwd=arm).code == 0
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    assert result.stderr.startswith(
        "mjcfbuild: error: mjcf/report/report.md: was edited since a build wrote it"
    )
    assert "(copy out what you need, then remove it (the report folder is the build's))" in (
        result.stderr
    )
    assert report.read_text().endswith("MY NOTES\n")
    # The build that stopped at it did not take it for its own: the next one stops too.
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == EXIT_OUTPUT
    assert report.read_text().endswith("MY NOTES\n")


def test_a_model_tuned_by_hand_is_kept_until_git_holds_the_edit(arm):
    """A model edited since the build wrote it is the user's (days of hand-tuning were lost to
    the next build): the build stops at it, every time, until the edit is committed (git then
    has it; the build says it wrote over it) or the file is moved away. A staged edit is not
    enough: the commit hook wrote over it, and `git add` as asked then lost it."""
    import subprocess

    def git(*args):
        command = ["git", "-c", "user.name=t", "-c", "user.email=t@t", *args]
        subprocess.run(command, cwd=arm, check=True, capture_output=True)

    git("init", "-q")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    model = arm / "mjcf" / "example_arm.xml"
    built = model.read_text()
    tuned = built.replace("<mujoco", "<!-- tuned -->\n<mujoco", 1)
    model.write_text(tuned)
    for staged in (False, True):
        if staged:
            git("add", "-A")
        result = run_cli("build", "-q", "--no-check", cwd=arm)
        assert result.code == EXIT_OUTPUT, result.stderr
        assert result.stderr == (
            "mjcfbuild: error: mjcf/example_arm.xml: was edited since a build wrote it, and git "
            "has no commit of the edit; a build never writes over an edit of yours (carry the "
            "edit into robot.yaml's mujoco_inputs or actuators, which every build applies, "
            "then remove the file; or commit it (past the commit hook: --no-verify), and the "
            "build writes over it)\n"
        )
        assert model.read_text() == tuned
    # What is checked and what a build would do say so (not "as it was built", "not run").
    checked = run_cli("check", cwd=arm)
    assert checked.code == 0, checked.stderr
    assert checked.stdout.splitlines()[-2].endswith(
        "of mjcf/example_arm.xml as edited by hand, not as the build wrote it (a build stops "
        "at the edit until it is carried into robot.yaml or committed)"
    ), checked.stdout
    dry = run_cli("build", "-n", "--no-check", cwd=arm)
    assert (
        "would run: assemble example_arm.xml: it stops at mjcf/example_arm.xml, edited by hand "
        "since it was built"
    ) in dry.stdout, dry.stdout
    # Committed: git has the edit, writing over it loses nothing, and the build says so;
    # check says what it checked.
    git("commit", "-qm", "tuned")
    checked = run_cli("check", cwd=arm)
    assert "of mjcf/example_arm.xml as git has it in HEAD, not as this folder's last build" in (
        checked.stdout
    )
    result = run_cli("build", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    assert (
        "mjcfbuild: wrote over mjcf/example_arm.xml, which held bytes git has in HEAD but no "
        "build here wrote (`git diff` shows what the build changed; keep a tuning in "
        "robot.yaml)"
    ) in result.stdout.splitlines()
    assert model.read_text() == built
    # Edited again (git has only the first edit), then moved away: the build writes it again.
    model.write_text(tuned.replace("tuned", "tuned again"))
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == EXIT_OUTPUT
    model.rename(arm / "tuned.xml")
    again = run_cli("build", "--no-check", cwd=arm)
    assert again.code == 0 and "wrote over" not in again.stdout, again.stdout
    assert model.read_text() == built


def test_a_fresh_clone_of_committed_models_is_the_builds_to_keep_current(arm):
    """A repository that commits its models (not the state folder): the first build of a
    fresh clone finds the model, scene and assets with no record, and updates them. It knows
    them by the model's header; a folder whose model lacks it is guarded as above."""
    import shutil

    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    shutil.rmtree(arm / "mjcf" / ".mjcfbuild")
    limits = arm / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    before = (arm / "mjcf" / "example_arm.xml").read_text()
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert (arm / "mjcf" / "example_arm.xml").read_text() != before
    shutil.rmtree(arm / "mjcf" / ".mjcfbuild")
    model = arm / "mjcf" / "example_arm.xml"
    model.write_text(model.read_text().split("\n", 1)[1])  # no header: not known as a build's
    limits.write_text(limits.read_text().replace("upper: 2.4", "upper: 2.3"))
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == EXIT_OUTPUT


def test_what_a_stopped_assembly_wrote_before_it_stopped_is_not_taken_for_an_edit(arm):
    """The assembly writes the assets, then refuses the edited model: the new asset bytes
    stood under the old record's hash, and once the model was moved away the next build
    stopped at the asset, which the user never touched."""
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    model = arm / "mjcf" / "example_arm.xml"
    model.write_text(model.read_text() + "<!-- tuned -->\n")
    mesh = arm / "meshes" / "forearm.obj"
    mesh.write_text(mesh.read_text().replace(" 0.240000", " 0.250000"))
    stopped = run_cli("build", "-q", "--no-check", cwd=arm)
    assert stopped.code == EXIT_OUTPUT and "example_arm.xml: was edited" in stopped.stderr
    mesh.write_text(mesh.read_text().replace(" 0.250000", " 0.260000"))  # new asset bytes
    model.unlink()
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    assert not (arm / "mjcf" / ".mjcfbuild" / "wrote.log").exists()


def test_without_a_record_an_output_that_is_not_heads_is_an_edit(arm):
    """A fresh clone of a repository that commits its models has no record of what builds
    wrote: a model tuned there was written over."""
    import shutil
    import subprocess

    def git(*args):
        command = ["git", "-c", "user.name=t", "-c", "user.email=t@t", *args]
        subprocess.run(command, cwd=arm, check=True, capture_output=True)

    git("init", "-q")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    git("add", "-A")
    git("commit", "-qm", "built")
    shutil.rmtree(arm / "mjcf" / ".mjcfbuild")  # as a clone has it
    model = arm / "mjcf" / "example_arm.xml"
    tuned = model.read_text().replace("<mujoco", "<!-- tuned -->\n<mujoco", 1)
    model.write_text(tuned)
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    assert model.read_text() == tuned


def test_a_picture_of_the_users_in_the_package_is_not_removed(tmp_path):
    """A build without previews removes the package picture it copied earlier; one the user
    put in its place was removed with it."""
    import shutil

    from tests.conftest import EXAMPLES

    arm = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  package: true\n")
    assert run_cli("build", "-q", cwd=arm).code == 0
    picture = arm / "mjcf" / "package" / "example_arm.png"
    picture.write_bytes(b"my own render")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert picture.read_bytes() == b"my own render"


def test_a_model_in_a_merge_conflict_is_rebuilt_and_said_so(arm):
    """Resolving robot.yaml's side of a conflict and building resolves the model's; the build
    said the model 'held bytes git has in HEAD', where it held conflict markers."""
    import subprocess

    def git(*args):
        command = ["git", "-c", "user.name=t", "-c", "user.email=t@t", *args]
        return subprocess.run(command, cwd=arm, capture_output=True)

    manifest = arm / "robot.yaml"
    git("init", "-q", "-b", "main")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    git("add", "-A")
    git("commit", "-qm", "built")
    for branch, elbow in (("other", "1.1"), ("main", "0.9")):
        git("checkout", "-q", "-B", branch)  # other from main; then main as it was
        manifest.write_text(re.sub(r"elbow: [-0-9.]+", f"elbow: {elbow}", manifest.read_text()))
        assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
        git("commit", "-qam", elbow)
        git("checkout", "-q", "main")
    assert git("merge", "-q", "other").returncode != 0  # robot.yaml and the model conflict
    git("checkout", "--theirs", "robot.yaml")
    git("add", "robot.yaml")
    result = run_cli("build", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    assert (
        "mjcfbuild: wrote over mjcf/example_arm.xml, which held a merge conflict (its markers): "
        "the built model resolves it (`git add` it)"
    ) in result.stdout.splitlines(), result.stdout
    assert "<<<<<<<" not in (arm / "mjcf" / "example_arm.xml").read_text()


def test_an_edit_git_cannot_give_back_survives_the_state_folder_removed(arm):
    """A model git ignores, tuned by hand, then `rm -rf mjcf/.mjcfbuild`: with no record,
    the build took the model for a fresh clone's and wrote over the tuning. The no-op stamp,
    kept outside the folder, still knows the bytes the build wrote."""
    import shutil

    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    model = arm / "mjcf" / "example_arm.xml"
    tuned = model.read_text().replace("<mujoco", "<!-- tuned -->\n<mujoco", 1)
    model.write_text(tuned)
    shutil.rmtree(arm / "mjcf" / ".mjcfbuild")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    assert "example_arm.xml: was edited" in result.stderr
    assert model.read_text() == tuned


def test_without_the_state_folder_no_output_a_build_wrote_is_taken_for_an_edit(arm):
    """The stamp of the other kind of build (with or without the check), or a report `check`
    rewrote, was taken for edits: the build stopped at files nobody edited."""
    import shutil

    for argv in (["--no-check"], [], ["--no-check"]):
        assert run_cli("build", "-q", *argv, cwd=arm).code == 0
        assert run_cli("check", "-q", cwd=arm).code == 0
        shutil.rmtree(arm / "mjcf" / ".mjcfbuild")
    for argv in ([], ["--no-check"]):
        result = run_cli("build", "-q", *argv, cwd=arm)
        assert result.code == 0, result.stderr
