"""Errors about a manifest key get the manifest's line, whichever way the manifest is named."""

from __future__ import annotations

from pathlib import Path

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.manifest.pinpoint import pinpoint

MANIFEST = """name: arm
source:
  urdf: robot.urdf
mujoco_inputs:
  raw: |
    <option integrator="implicitfast"/>
    <actuator><motor joint='hinge'>
"""


@pytest.mark.parametrize("named", ["command line", "own folder"])
def test_a_raw_block_error_points_at_its_line(tmp_path: Path, named: str):
    manifest = tmp_path / "robot.yaml"
    manifest.write_text(MANIFEST)
    # The engine names the manifest as the command line did; steps name it as "robot.yaml".
    label = str(manifest) if named == "command line" else "robot.yaml"
    error = InputError("malformed XML", file=f"{label} mujoco_inputs.raw", line=2)
    pinpoint(error, str(manifest), manifest)
    assert error.one_line() == "robot.yaml:7: mujoco_inputs.raw: malformed XML"


def test_an_error_about_another_file_is_left_alone(tmp_path: Path):
    manifest = tmp_path / "robot.yaml"
    manifest.write_text(MANIFEST)
    error = InputError("bad", file="robot.urdf", line=3)
    pinpoint(error, str(manifest), manifest)
    assert error.one_line() == "robot.urdf:3: bad"


@pytest.mark.parametrize("key", ["*finger*", "arm/joint:1", "l_hip-yaw", "0"])
def test_a_key_that_is_no_identifier_points_at_its_line(tmp_path: Path, key: str):
    """A home: key may be a glob or a joint name with any characters but dots."""
    manifest = tmp_path / "robot.yaml"
    manifest.write_text(f'{MANIFEST}home:\n  shoulder: 0.5\n  "{key}": 1.0\n')
    error = InputError("matches no moving joint", file=f"robot.yaml home.{key}")
    pinpoint(error, "robot.yaml", manifest)
    assert error.one_line() == f"robot.yaml:10:3: home.{key}: matches no moving joint"


def test_a_key_with_dots_is_written_in_brackets_and_points_at_its_line(tmp_path: Path):
    """A file name as a key (meshes.collada_up_axis_files) has dots in it."""
    from mjcfbuild.manifest.pinpoint import key_path, key_segment

    assert key_segment("torso.dae") == '["torso.dae"]' and key_segment("elbow") == ".elbow"
    assert key_path('meshes.files["a.dae"]') == ("meshes", "files", "a.dae")
    manifest = tmp_path / "robot.yaml"
    manifest.write_text(f"{MANIFEST}meshes:\n  collada_up_axis_files:\n    arm.dae: ignore\n")
    key = f"meshes.collada_up_axis_files{key_segment('arm.dae')}"
    error = InputError("matches no mesh file", file=f"robot.yaml {key}")
    pinpoint(error, "robot.yaml", manifest)
    assert error.one_line() == f"robot.yaml:10:5: {key}: matches no mesh file"
