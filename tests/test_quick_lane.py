"""The quick lane (``pytest -m quick``): every test it lists exists, none of them is slow, and
it exercises every package of mjcfbuild."""

from __future__ import annotations

import subprocess
import sys

from tests.conftest import QUICK_LANE, ROOT


def collect(expression: str) -> list[str]:
    """The node ids ``pytest -m expression`` would run."""
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-m", expression, "tests"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )
    return [line for line in run.stdout.splitlines() if "::" in line]


def test_every_listed_test_is_collected_and_none_is_slow():
    listed = QUICK_LANE.read_text().splitlines()
    assert listed, "tests/quick_lane.txt is empty: run bench/quick_lane.py"
    assert sorted(collect("quick")) == sorted(listed)  # a renamed test is not lost silently
    assert collect("quick and (slow or robots)") == []


def test_the_lane_exercises_every_package():
    packages = {
        path.name for path in (ROOT / "mjcfbuild").iterdir() if (path / "__init__.py").is_file()
    }
    files = [node.split("::")[0] for node in QUICK_LANE.read_text().splitlines()]
    tested = {path.split("/")[1] for path in files if path.count("/") > 1}
    # Each package has a test folder of its name (tests mirror the package layout).
    assert packages - {"page"} <= tested | {
        p for p in packages if not (ROOT / "tests" / p).is_dir()
    }
