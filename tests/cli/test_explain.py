"""``mjcfbuild explain`` and ``build --dry-run``: why tasks would run, without running them."""

from __future__ import annotations

from tests.conftest import run_cli


def test_explain_names_the_changed_input_and_nothing_else(arm):
    assert run_cli("build", "-q", cwd=arm).code == 0
    (arm / "meshes" / "forearm_colours.mtl").write_text(
        (arm / "meshes" / "forearm_colours.mtl").read_text() + "# edited\n"
    )
    result = run_cli("explain", cwd=arm)
    assert result.code == 0
    lines = result.stdout.splitlines()
    assert "mesh:forearm: would run" in lines
    assert "  - input changed: meshes/forearm_colours.mtl" in lines
    assert "mesh:base: up to date" in lines and "assemble: up to date" in lines
    one = run_cli("explain", "mesh:forearm", cwd=arm)
    assert one.stdout.splitlines() == [
        "mesh:forearm: would run",
        "  - input changed: meshes/forearm_colours.mtl",
        "  then, where what it writes comes out changed: assemble example_arm.xml, scene "
        "scene.xml, check example_arm.xml, previews, tuning report",
    ]
    # The dry run says the same: the tasks that read the mesh may follow it.
    dry = run_cli("build", "-n", cwd=arm)
    assert "  then, where what it writes comes out changed: assemble example_arm.xml" in dry.stdout


def test_explain_names_a_changed_parameter(arm):
    assert run_cli("build", "-q", cwd=arm).code == 0
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "meshes:\n  max_faces: 500\n")
    result = run_cli("explain", "mesh:upper_arm", cwd=arm)
    assert "mesh:upper_arm: would run" in result.stdout
    assert "  - parameters changed: options.max_faces" in result.stdout


def test_explain_before_the_first_build_writes_nothing(arm):
    result = run_cli("explain", cwd=arm)
    assert result.code == 0
    assert "expand: would run\n  - it has not run in this output folder yet" in result.stdout
    assert not (arm / "mjcf").exists()


def test_dry_run_lists_what_would_run_and_runs_nothing(arm):
    assert run_cli("build", "-q", cwd=arm).code == 0
    limits = arm / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    model = (arm / "mjcf" / "example_arm.xml").read_bytes()
    result = run_cli("build", "--dry-run", cwd=arm)
    assert result.code == 0
    assert "would run: expand urdf/arm.urdf.xacro: input changed: config/joint_limits.yaml" in (
        result.stdout
    )
    assert result.stdout.strip().endswith("(dry run)")
    assert (arm / "mjcf" / "example_arm.xml").read_bytes() == model
    assert "expand: would run" in run_cli("explain", "expand", cwd=arm).stdout


def test_the_manifest_is_a_positional_argument_in_either_order_with_the_task(arm, tmp_path):
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    manifest = str(arm / "robot.yaml")
    whole = run_cli("explain", manifest, cwd=tmp_path)
    assert whole.code == 0, whole.stderr
    assert "mesh:base: up to date" in whole.stdout
    for argv in ([manifest, "mesh:base"], ["mesh:base", manifest], ["mesh:base", "-m", manifest]):
        one = run_cli("explain", *argv, cwd=tmp_path)
        assert one.code == 0, one.stderr
        assert one.stdout.splitlines() == ["mesh:base: up to date"]
    # A manifest with another name is recognised because the file exists.
    renamed = arm / "arm.manifest"
    renamed.write_text((arm / "robot.yaml").read_text())
    assert run_cli("explain", "arm.manifest", "mesh:base", cwd=arm).code == 0
    two = run_cli("explain", "robot.yaml", "arm.manifest", cwd=arm)
    assert two.code == 2 and "one manifest" in two.stderr
    both = run_cli("explain", "robot.yaml", "-m", "arm.manifest", cwd=arm)
    assert both.code == 2 and "two manifests" in both.stderr


def test_a_misspelt_task_gets_the_closest_name(arm):
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    result = run_cli("explain", "mesh:bse", cwd=arm)
    assert result.code == 2
    assert "no task 'mesh:bse'; did you mean 'mesh:base'? tasks: expand, plan" in result.stderr


def test_a_folder_for_the_manifest_is_refused_in_the_words_of_build(arm, tmp_path):
    (tmp_path / "some_folder").mkdir()
    refused = run_cli("build", "some_folder", cwd=tmp_path)
    assert refused.code == 3
    assert refused.stderr.startswith("mjcfbuild: error: some_folder: this is a folder")
    for argv in (["some_folder"], ["some_folder", "mesh:base"], ["mesh:base", "some_folder"]):
        result = run_cli("explain", *argv, cwd=tmp_path)
        assert (result.code, result.stderr) == (refused.code, refused.stderr), argv
    # Beside a robot.yaml, a folder named like a task is the task.
    (arm / "plan").mkdir()
    task = run_cli("explain", "plan", cwd=arm)
    assert task.code == 0, task.stderr
    assert task.stdout.startswith("plan: would run")
