"""Where a build's warnings point (mjcfbuild/engine/placing.py): the console and the report
name a xacro source's file and line alike."""

from __future__ import annotations

import re
from pathlib import Path

from tests.conftest import run_cli, write

# A plate welded to the world whose inertia breaks A + B >= C, written inside a macro: the
# check warns about it (MuJoCo ignores the world's mass properties), at the expanded line.
XACRO = """<?xml version="1.0"?>
<robot name="plated" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="plate" params="name">
    <link name="${name}">
      <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.05" ixy="0" ixz="0" iyz="0"/></inertial>
      <collision><geometry><box size="0.2 0.2 0.02"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="world"/>
  <xacro:plate name="base"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.03" length="0.5"/></geometry></collision>
  </link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
</robot>
"""
WARNING = "link 'base': its principal moments 0.01, 0.01, 0.05 break A + B >= C"


def _plated(folder: Path) -> Path:
    write(folder / "robot.urdf.xacro", XACRO)
    write(folder / "robot.yaml", "name: plated\nsource:\n  xacro: robot.urdf.xacro\n")
    return folder


def _console_warning(stderr: str) -> str:
    (line,) = [line for line in stderr.splitlines() if WARNING in line and "warning:" in line]
    return line.removeprefix("mjcfbuild: warning: ")


def test_the_report_names_a_check_warnings_xacro_line_as_the_console_does(tmp_path):
    folder = _plated(tmp_path)
    built = run_cli("build", cwd=folder)
    assert built.code == 0, built.stderr
    console = _console_warning(built.stderr)
    # Where the console points: the macro's <inertial>, then the expanded line.
    assert console.startswith(f"robot.urdf.xacro:5: {WARNING}"), console
    assert console.endswith("[expanded: mjcf/.mjcfbuild/source.urdf:9]"), console
    report = (folder / "mjcf" / "report" / "report.md").read_text()
    (listed,) = [line for line in report.splitlines() if line.startswith("- ") and WARNING in line]
    assert _plain(listed.removeprefix("- ")) == console
    verdict = next(line for line in report.splitlines() if line.startswith("Result: "))
    assert "(see Warnings): robot.urdf.xacro:5: link 'base'" in verdict, verdict
    (row,) = [line for line in report.splitlines() if line.startswith("| link base (")]
    assert row.startswith("| link base (robot.urdf.xacro:5) | warning |"), row
    assert "source.urdf:9:" not in report and "(mjcf/.mjcfbuild/source.urdf" not in report
    # `mjcfbuild check` names it there too, in its warnings and its verdict.
    checked = run_cli("check", cwd=folder)
    assert checked.code == 0, checked.stderr
    assert _console_warning(checked.stderr) == console
    assert f"checks pass with 1 warning: robot.urdf.xacro:5: {WARNING}" in checked.stdout
    assert (folder / "mjcf" / "report" / "report.md").read_text() == report


def _plain(markdown: str) -> str:
    """A line of report.md without Markdown's backslash escapes."""
    return re.sub(r"\\([!-/:-@\[-`{-~])", r"\1", markdown)


def test_a_report_written_outside_robot_yaml_s_folder_names_no_absolute_path(tmp_path):
    # The expanded URDF lies in the output folder; outside robot.yaml's folder it was named by
    # its absolute path, so the report differed from one checkout to the next.
    folder = _plated(tmp_path / "robot")
    with (folder / "robot.yaml").open("a") as manifest:
        manifest.write("output:\n  folder: ../out\n  allow_outside: true\n")
    built = run_cli("build", cwd=folder)
    assert built.code == 0, built.stderr
    report = (tmp_path / "out" / "report" / "report.md").read_text()
    assert "[expanded: ../out/.mjcfbuild/source.urdf:9]" in report
    assert str(tmp_path) not in report
