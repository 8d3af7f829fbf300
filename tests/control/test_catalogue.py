"""Finding motors by name: robot.yaml's definitions, then the users' files in order, then the
shipped catalogue; a missing file or an unknown name is a robot.yaml error."""

from __future__ import annotations

import pytest

from mjcfbuild.control.catalogue import resolve_motors
from mjcfbuild.errors import InputError
from mjcfbuild.manifest.motors import MotorSettings
from mjcfbuild.manifest.simulation import ActuatorRule
from tests.conftest import write


def _rules(*motors: str) -> list[ActuatorRule]:
    return [ActuatorRule(joints=[f"j{i}"], motor=m) for i, m in enumerate(motors)]


def test_definitions_win_over_files_which_win_over_the_catalogue(tmp_path):
    write(tmp_path / "a.yaml", "go1_knee: {rotor_inertia: 1.0, peak_torque: 1}\n")
    write(
        tmp_path / "b.yaml",
        "go1_knee: {rotor_inertia: 2.0, peak_torque: 2}\nx: {rotor_inertia: 3.0, peak_torque: 3}\n",
    )
    settings = MotorSettings(
        files=["a.yaml", "b.yaml"],
        define={"x": {"rotor_inertia": 4.0, "peak_torque": 4}},
    )
    found = resolve_motors(settings, _rules("go1_knee", "x", "go1_hip"), tmp_path, "robot.yaml")
    assert found["go1_knee"]["rotor_inertia"] == 1.0  # the first file
    assert found["x"]["rotor_inertia"] == 4.0  # robot.yaml's own
    assert found["go1_hip"]["rotor_inertia"] == pytest.approx(0.000111842)  # the catalogue
    assert set(found) == {"go1_knee", "x", "go1_hip"}  # only what the rules name


def test_a_missing_motor_file_is_an_error_even_before_a_rule_names_a_motor(tmp_path):
    with pytest.raises(InputError) as caught:  # a missing input: exit 4, as a missing source
        resolve_motors(MotorSettings(files=["gone.yaml"]), [], tmp_path, "robot.yaml")
    assert "motor file 'gone.yaml' not found" in caught.value.one_line()
    assert "robot.yaml motors.files[0]" in caught.value.one_line()


def test_no_motors_reads_nothing(tmp_path):
    assert resolve_motors(MotorSettings(), _rules(), tmp_path, "robot.yaml") == {}
