"""The build report (mjcfbuild/engine/report.py) lists every warning the model deserves, also
after a rebuild in which the tasks that gave them were up to date."""

from __future__ import annotations

import json

from tests.cli.test_warning_groups import padded_robot
from tests.conftest import run_cli


def test_the_report_keeps_warnings_of_tasks_that_did_not_run_again(tmp_path):
    folder = padded_robot(tmp_path)
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    # Now the check and previews run; the assembly that warned is up to date.
    again = run_cli("build", cwd=folder)
    assert again.code == 0, again.stderr
    assert "mjcfbuild: warning:" not in again.stderr  # the console says what is new
    report = json.loads((folder / "mjcf" / "report" / "report.json").read_text())
    assert report["warnings"] == [
        f"robot.urdf:15: link 'pad{i}' visual 0 has box size 0 0 0; dropped it" for i in range(8)
    ]
    text = (folder / "mjcf" / "report" / "report.md").read_text()
    listed = [line for line in text.splitlines() if line.startswith("- ") and "box size" in line]
    assert len(listed) == 8


def test_a_warning_fixed_in_the_source_leaves_the_report(tmp_path):
    folder = padded_robot(tmp_path)
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    urdf = folder / "robot.urdf"
    urdf.write_text(urdf.read_text().replace('size="0 0 0"', 'size="0.1 0.1 0.1"'))
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    report = json.loads((folder / "mjcf" / "report" / "report.json").read_text())
    assert report["warnings"] == []
