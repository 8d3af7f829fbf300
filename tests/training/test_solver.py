"""The variant's solver settings: each device's defaults, and the user's settings over them."""

from __future__ import annotations

import pytest

from mjcfbuild.training.solver import SolverSettings, solver_settings


@pytest.mark.parametrize(
    ("device", "expected"),
    [("gpu", SolverSettings("newton", 1, 5)), ("cpu", SolverSettings("cg", 2, 4))],
)
def test_each_device_has_its_measured_defaults(device, expected):
    assert solver_settings(device) == expected


def test_given_settings_replace_only_their_own_default():
    assert solver_settings("gpu", iterations=3) == SolverSettings("newton", 3, 5)
    assert solver_settings("cpu", solver="newton") == SolverSettings("newton", 2, 4)
    assert solver_settings("gpu", "cg", 2, 4) == SolverSettings("cg", 2, 4)
