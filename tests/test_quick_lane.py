"""The quick lane (``pytest -m quick``): every test it lists exists, none of them is slow, and
it exercises every package of mjcfbuild."""

from __future__ import annotations

import subprocess
import sys

from tests.conftest import QUICK_LANE, ROOT
from tests.quick_lane_probe import PREFIX


def collect(expression: str) -> dict[str, bool]:
    """The node ids ``pytest -m expression`` would run, each with whether it is marked slow or
    robots (told by tests/quick_lane_probe.py)."""
    probe = ["-p", "tests.quick_lane_probe"]
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", *probe, "-m", expression, "tests"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    found = {}
    for line in run.stdout.splitlines():
        if line.startswith(PREFIX):
            weight, node = line.removeprefix(PREFIX).split(maxsplit=1)
            found[node] = weight == "heavy"
    return found


def test_every_listed_test_is_collected_and_none_is_slow():
    listed = QUICK_LANE.read_text().splitlines()
    assert listed, "tests/quick_lane.txt is empty: run bench/quick_lane.py"
    quick = collect("quick")
    assert sorted(quick) == sorted(listed)  # a renamed test is not lost silently
    assert [node for node, heavy in quick.items() if heavy] == []


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
