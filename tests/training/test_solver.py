"""The variant's solver settings: the device picks the solver, the solver its iteration caps,
and what the user gives replaces only its own default."""

from __future__ import annotations

import pytest

from mjcfbuild.training.solver import SolverSettings, solver_settings


@pytest.mark.parametrize(
    ("device", "expected"),
    [("gpu", SolverSettings("newton", 1, 5)), ("cpu", SolverSettings("cg", 2, 4))],
)
def test_each_device_has_its_defaults(device, expected):
    assert solver_settings(device) == expected


def test_a_given_solver_brings_its_own_iteration_caps():
    assert solver_settings("cpu", solver="newton") == SolverSettings("newton", 1, 5)
    assert solver_settings("gpu", solver="cg") == SolverSettings("cg", 2, 4)


def test_given_caps_replace_only_their_own_default():
    assert solver_settings("gpu", iterations=3) == SolverSettings("newton", 3, 5)
    assert solver_settings("cpu", ls_iterations=8) == SolverSettings("cg", 2, 8)
    assert solver_settings("cpu", "newton", 4, 8) == SolverSettings("newton", 4, 8)
