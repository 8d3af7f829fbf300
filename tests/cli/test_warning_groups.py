"""Where builds print warnings one line per kind (mjcfbuild/warning_groups.py):
``build`` (not with ``-q``) and ``diff`` (after its answer, once, not with ``-q``)."""

from __future__ import annotations

import subprocess
from pathlib import Path

from tests.conftest import run_cli, simple_manifest, two_link_urdf, write

PADS = "".join(
    f'<link name="pad{i}"><visual><geometry><box size="0 0 0"/></geometry></visual></link>'
    f'<joint name="pad{i}_fix" type="fixed"><parent link="arm"/><child link="pad{i}"/></joint>'
    for i in range(8)
)


def padded_robot(folder: Path) -> Path:
    """A robot with 8 zero-size visual boxes, each one a warning; its folder."""
    write(folder / "robot.urdf", two_link_urdf(PADS))
    simple_manifest(folder)
    return folder


def warning_lines(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if line.startswith("mjcfbuild: warning:")]


def test_build_prints_eight_zero_size_boxes_as_one_line_and_the_report_lists_all(tmp_path):
    folder = padded_robot(tmp_path)
    result = run_cli("build", "--no-check", cwd=folder)
    assert result.code == 0, result.stderr
    assert warning_lines(result.stderr) == [
        "mjcfbuild: warning: robot.urdf:15: 8 × link '…' visual 0 has box size 0 0 0; "
        "dropped it: pad0, pad1, pad2, ... 5 more (all in mjcf/report/report.md)"
    ]
    assert "8 warnings" in result.stdout
    report = (folder / "mjcf" / "report" / "report.md").read_text()
    assert all(f"link 'pad{i}' visual 0 has box size 0 0 0" in report for i in range(8))


def test_quiet_build_prints_errors_only(tmp_path):
    folder = padded_robot(tmp_path)
    result = run_cli("build", "--no-check", "-q", cwd=folder)
    assert result.code == 0 and result.stdout == "" and result.stderr == ""
    (folder / "robot.urdf").write_text(
        two_link_urdf(PADS).replace('link="arm"/><child', 'link="arn"/><child', 1)
    )
    failed = run_cli("build", "--no-check", "-q", cwd=folder)
    assert failed.code == 4
    assert failed.stderr.startswith("mjcfbuild: error: robot.urdf:")
    assert not warning_lines(failed.stderr)


def test_diff_prints_the_warnings_once_after_the_answer_and_none_with_quiet(tmp_path):
    folder = padded_robot(tmp_path / "repo")
    (folder / ".gitignore").write_text("mjcf/\n")
    git = ["git", "-c", "user.email=t@example.com", "-c", "user.name=t"]
    subprocess.run([*git, "init", "-q", "-b", "main"], cwd=folder, check=True)
    subprocess.run([*git, "add", "."], cwd=folder, check=True)
    subprocess.run([*git, "commit", "-qm", "robot"], cwd=folder, check=True)
    scratch = str(tmp_path / "scratch")
    argv = ("diff", "--base", "main", "--scratch", scratch)
    result = run_cli(*argv, cwd=folder)
    assert result.code == 0, result.stderr
    lines = result.stderr.splitlines()
    warned = warning_lines(result.stderr)
    assert len(warned) == 1, result.stderr
    assert warned[0].startswith("mjcfbuild: warning: main (")
    assert warned[0].endswith(
        ") and the working tree: robot.urdf:15: 8 × link '…' visual 0 has "
        "box size 0 0 0; dropped it: pad0, pad1, pad2, ... 5 more"
    )
    assert lines[-1] == warned[0]  # after the builds' lines, as the last word
    quiet = run_cli(*argv, "-q", cwd=folder)
    assert quiet.code == 0 and quiet.stderr == "", quiet.stderr
    assert quiet.stdout == result.stdout
