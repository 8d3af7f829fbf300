"""The model file's digits set how finely its numbers are compared."""

from __future__ import annotations

from mjcfbuild.check.precision import relative_tolerance, significant_digits
from tests.conftest import write


def test_significant_digits_as_written():
    assert [significant_digits(t) for t in ("1.97222", "3.68001e-05", "0.00368001")] == [6, 6, 6]
    assert significant_digits("0.333333333333") == 12 and significant_digits("100") == 1


def test_tolerance_follows_the_files_digits_unless_asked(tmp_path):
    six = write(tmp_path / "six.xml", '<mujoco><joint range="-1.97222 1.97222"/></mujoco>')
    twelve = write(tmp_path / "twelve.xml", '<mujoco><joint range="-1.97222222222 1"/></mujoco>')
    assert relative_tolerance(six, None) == 1e-5
    assert relative_tolerance(twelve, None) == 1e-6
    assert relative_tolerance(six, 1e-8) == 1e-8
