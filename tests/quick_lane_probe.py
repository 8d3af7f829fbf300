"""A pytest plugin for tests/test_quick_lane.py (``-p tests.quick_lane_probe``): once the tests
are collected and selected, it prints one line per test: its node id and whether it is marked
slow or robots. One collection then answers what took two (``-m quick`` and ``-m "quick and
(slow or robots)"``: about 10 s each)."""

from __future__ import annotations

import pytest

PREFIX = "quick-lane-probe:"


def pytest_collection_finish(session: pytest.Session) -> None:
    """Print ``quick-lane-probe: heavy|light <node id>`` for every selected test."""
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    for item in session.items:
        heavy = any(item.get_closest_marker(name) for name in ("slow", "robots"))
        reporter.write_line(f"{PREFIX} {'heavy' if heavy else 'light'} {item.nodeid}")
