"""``mjcfbuild clean``: everything a build wrote goes, and nothing else."""

from __future__ import annotations

from tests.conftest import run_cli


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


def test_the_manifest_is_a_positional_argument(arm, tmp_path):
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    result = run_cli("clean", str(arm / "robot.yaml"), cwd=tmp_path)
    assert result.code == 0, result.stderr
    assert not (arm / "mjcf").exists()


def test_quiet_before_or_after_the_command_prints_nothing(arm):
    for argv in (["-q", "clean"], ["clean", "-q"]):
        assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
        result = run_cli(*argv, cwd=arm)
        assert result.code == 0 and result.stdout == "", result.stdout
        assert not (arm / "mjcf").exists()
