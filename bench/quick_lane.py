"""Choose the quick test lane from a full run's timings: ``tests/quick_lane.txt``.

    python -m pytest --junitxml=/tmp/run.xml          # a full run, any machine
    python bench/quick_lane.py /tmp/run.xml [--budget 120]

It also writes each test file's measured seconds, slowest first, to ``tests/file_seconds.txt``:
tests/conftest.py starts the slowest files first, so that a run in two workers does not end
with one of them alone on a long file.

The lane takes no test marked slow or robots (real robots, CoACD), and none from the files that
drive a browser or MuJoCo Warp / MJX. Of the rest it takes the fastest test of every test module
first (so every package of mjcfbuild is exercised), then the fastest remaining ones, until their
measured times add up to ``--budget`` seconds. It prints the lane's size and measured time per
package; ``pytest -m quick`` runs it (tests/conftest.py marks the listed tests).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import xml.etree.ElementTree as ElementTree
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LANE = ROOT / "tests" / "quick_lane.txt"
FILE_SECONDS = ROOT / "tests" / "file_seconds.txt"
# Words in a test file that say it drives a browser, MuJoCo Warp or MJX (heavy imports and
# kernel compiles) or fetches from npm: such files stay out of the lane.
LEFT_OUT = ("chromium", "warp", "mjx", "npm")


def timings(report: Path) -> dict[str, float]:
    """Node id -> seconds, for every test that passed in the junit ``report``."""
    times = {}
    for case in ElementTree.parse(report).getroot().iter("testcase"):
        if any(child.tag in ("skipped", "failure", "error") for child in case):
            continue
        node = _node_id(case.get("classname", ""), case.get("name", ""))
        if node:
            times[node] = float(case.get("time", "0"))
    return times


def _node_id(classname: str, name: str) -> str | None:
    """``tests.check.test_x.TestY`` and ``test_z`` -> ``tests/check/test_x.py::TestY::test_z``."""
    parts = classname.split(".")
    for cut in range(len(parts), 0, -1):
        path = Path(*parts[:cut]).with_suffix(".py")
        if (ROOT / path).is_file():
            return "::".join([path.as_posix(), *parts[cut:], name])
    return None


def fast_tests() -> set[str]:
    """The node ids outside the slow and robots markers."""
    collected = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-m", "not slow and not robots"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    return {line for line in collected.stdout.splitlines() if "::" in line}


def choose(times: dict[str, float], allowed: set[str], budget: float) -> list[str]:
    """The fastest test of each module, then the fastest others, within ``budget`` seconds."""
    files = {node.split("::")[0] for node in times}
    heavy = {f for f in files if any(w in (ROOT / f).read_text().lower() for w in LEFT_OUT)}
    candidates = {
        node: seconds
        for node, seconds in times.items()
        if node in allowed and node.split("::")[0] not in heavy
    }
    by_module: dict[str, list[str]] = defaultdict(list)
    for node in sorted(candidates, key=lambda n: (candidates[n], n)):
        by_module[node.split("::")[0]].append(node)
    chosen = [tests[0] for _, tests in sorted(by_module.items())]
    spent = sum(candidates[node] for node in chosen)
    for node in sorted(candidates, key=lambda n: (candidates[n], n)):
        if node in chosen:
            continue
        if spent + candidates[node] > budget:
            break
        chosen.append(node)
        spent += candidates[node]
    return sorted(chosen)


def by_file(times: dict[str, float]) -> list[tuple[str, float]]:
    """Each test file with the seconds its tests took, slowest first."""
    seconds: dict[str, float] = defaultdict(float)
    for node, spent in times.items():
        seconds[node.split("::")[0]] += spent
    return sorted(seconds.items(), key=lambda item: (-item[1], item[0]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("report", type=Path, help="junit XML of a full pytest run")
    parser.add_argument("--budget", type=float, default=120.0, help="seconds of test time")
    args = parser.parse_args()
    times = timings(args.report)
    lane = choose(times, fast_tests(), args.budget)
    LANE.write_text("".join(f"{node}\n" for node in lane))
    FILE_SECONDS.write_text("".join(f"{seconds:.1f} {path}\n" for path, seconds in by_file(times)))
    per_package: dict[str, list[float]] = defaultdict(list)
    for node in lane:
        path = node.split("::")[0]
        package = path.split("/")[1] if path.count("/") > 1 else "(top)"
        per_package[package].append(times[node])
    print("| package | tests | measured s |")
    print("|---|---:|---:|")
    for package, seconds in sorted(per_package.items()):
        print(f"| {package} | {len(seconds)} | {sum(seconds):.1f} |")
    total = sum(times[node] for node in lane)
    print(f"| all | {len(lane)} | {total:.1f} |")


if __name__ == "__main__":
    main()
