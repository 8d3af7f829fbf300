"""The outside programs tests need: a missing one skips the test, except in CI, where it fails."""

from __future__ import annotations

import pytest

from tests.executables import require
from tests.urdfdom import find_check_urdf, require_urdfdom


def test_a_missing_program_skips_the_test_with_the_reason(monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    with pytest.raises(pytest.skip.Exception, match="no frobnicator"):
        require(None, "no frobnicator on PATH")


def test_a_missing_program_fails_the_test_in_ci(monkeypatch):
    monkeypatch.setenv("CI", "true")
    with pytest.raises(pytest.fail.Exception, match="CI: no frobnicator"):
        require(None, "no frobnicator on PATH")


def test_a_found_program_is_given_back():
    assert require("/bin/sh", "unused") == "/bin/sh"


def test_without_check_urdf_the_urdfdom_tests_are_skipped_or_fail_in_ci(monkeypatch):
    monkeypatch.setenv("PATH", "/nonexistent")
    assert find_check_urdf() is None
    monkeypatch.delenv("CI", raising=False)
    with pytest.raises(pytest.skip.Exception, match="apt-get install liburdfdom-tools"):
        require_urdfdom()
    monkeypatch.setenv("CI", "true")
    with pytest.raises(pytest.fail.Exception, match="CI: no check_urdf on PATH"):
        require_urdfdom()
