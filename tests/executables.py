"""The outside programs some tests need (a browser, ROS's URDF parser): without one such a test
is skipped with the reason, except in CI (``CI=true``, where .ci/run installs them all), where
that fails the test instead of hiding it."""

from __future__ import annotations

import os


def require(executable: str | None, reason: str) -> str:
    """``executable`` if found; otherwise skip the test with ``reason``, or fail it in CI."""
    import pytest

    if executable is None:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI: {reason}")
        pytest.skip(reason)
    return executable
