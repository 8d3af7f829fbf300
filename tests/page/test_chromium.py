"""The browser the page's tests use: skipped without one, except in CI, where that fails."""

from __future__ import annotations

import pytest

from tests.page import chromium


@pytest.fixture
def no_browser(monkeypatch):
    monkeypatch.setattr(chromium, "NAMES", ("no-such-browser-here",))
    monkeypatch.setenv("MJCFBUILD_CHROMIUM", "no-such-browser-either")


def test_without_a_browser_the_tests_are_skipped_with_the_reason(no_browser, monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    with pytest.raises(pytest.skip.Exception, match="no chromium on PATH"):
        chromium.require_chromium()


def test_without_a_browser_in_ci_the_tests_fail(no_browser, monkeypatch):
    monkeypatch.setenv("CI", "true")
    with pytest.raises(pytest.fail.Exception, match="CI: no chromium on PATH"):
        chromium.require_chromium()


def test_a_browser_named_by_the_setting_is_used(monkeypatch):
    monkeypatch.setattr(chromium, "NAMES", ())
    monkeypatch.setenv("MJCFBUILD_CHROMIUM", "sh")  # any executable on PATH: it is not started
    found = chromium.find_chromium()
    assert found is not None and found.endswith("/sh")
