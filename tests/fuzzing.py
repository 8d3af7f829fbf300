"""How many examples property tests run, and whether they are random.

The default test run is deterministic: hypothesis derandomized, no example database, so a
clean clone and CI see the same examples every time. ``MJCFBUILD_FUZZ=N`` turns on the long
fuzz run: random examples, N times as many, failures remembered in ``.hypothesis/``::

    MJCFBUILD_FUZZ=20 .venv/bin/python -m pytest -k fuzz
"""

from __future__ import annotations

import os

from hypothesis import settings

DETERMINISTIC = "deterministic"
RANDOM = "fuzz"


def fuzz_factor() -> int:
    """N from ``MJCFBUILD_FUZZ=N`` (0 when the long fuzz run is off)."""
    text = os.environ.get("MJCFBUILD_FUZZ", "").strip()
    return max(0, int(text)) if text.isdigit() else 0


def examples(count: int) -> int:
    """``count`` examples in the default run, ``count * N`` in the long fuzz run."""
    return count * max(1, fuzz_factor())


def load_profile() -> str:
    """Register both profiles and load the one this run asks for; its name."""
    settings.register_profile(DETERMINISTIC, derandomize=True, database=None, print_blob=True)
    settings.register_profile(RANDOM, derandomize=False, print_blob=True)
    name = RANDOM if fuzz_factor() else DETERMINISTIC
    settings.load_profile(name)
    return name
