"""The no-op of ``mjcfbuild convert`` and ``mjcfbuild build`` side by side.

    python bench/noop_times.py [--robots panda,go1,g1] [--repeat 7] [--jobs 2]

Each robot of example-robot-data is built once with ``mjcfbuild build`` (from a manifest) and
converted once with ``mjcfbuild convert`` (the reference converter's flags), each into its own
folder, with a private cache. Then nothing changes and each command runs ``--repeat`` more
times, alternating; the medians are shown, timed from the outside as a script calling them
would see it. Both no-ops take the same fast path: the stamp of the last successful build
(mjcfbuild.engine.stamp), keyed for ``convert`` by its folder and options.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench.build_times import compile_package
from bench.robot_data import ROBOTS, manifest, package_root, unpack


def timed(argv: list[str], cwd: Path, env: dict[str, str]) -> tuple[float, str]:
    """Wall-clock seconds of one ``mjcfbuild`` command and its last summary line."""
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", *argv], cwd=cwd, capture_output=True, text=True, env=env
    )
    seconds = time.perf_counter() - started
    if done.returncode != 0:
        raise SystemExit(f"mjcfbuild {' '.join(argv)} failed:\n{done.stderr}")
    lines = [line for line in done.stdout.splitlines() if line.startswith("mjcfbuild:")]
    return seconds, (lines[-1] if lines else "")


def measure(name: str, folder: Path, repeat: int, jobs: int, env: dict[str, str]) -> dict:
    """The median no-op seconds of ``build`` and ``convert`` for one robot."""
    robot = ROBOTS[name]
    urdf = unpack(robot)
    build = ["build", str(manifest(robot, folder / "build", urdf, package_root())), "-j", str(jobs)]
    convert = ["convert", "-u", str(urdf), "-o", str(folder / "convert"), "-j", str(jobs)]
    convert += ["--package", f"example-robot-data={package_root()}"]
    convert += ["-f"] if robot.floating else []
    for argv in (build, convert):
        timed(argv, folder, env)  # the first build
    times: dict[str, list[float]] = {"build": [], "convert": []}
    for _ in range(repeat):
        for key, argv in (("build", build), ("convert", convert)):
            seconds, summary = timed(argv, folder, env)
            if " 0 run," not in summary:
                raise SystemExit(f"{name}: {key} was not a no-op: {summary}")
            times[key].append(seconds)
    return {key: statistics.median(values) for key, values in times.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="panda,go1,g1", help="example-robot-data robots")
    parser.add_argument("--repeat", type=int, default=7, help="no-op runs of each (median)")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    compile_package()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        env = {**os.environ, "XDG_CACHE_HOME": str(Path(scratch) / "cache")}
        env["MJCFBUILD_RESIDENT_WORKERS"] = "0"  # no worker left behind by the first builds
        for name in [n for n in args.robots.split(",") if n]:
            rows.append((name, measure(name, Path(scratch) / name, args.repeat, args.jobs, env)))
            print(f"measured {name}", file=sys.stderr)
    print("| robot | `convert` no-op (s) | `build` no-op (s) |")
    print("|---|---:|---:|")
    for name, row in rows:
        print(f"| {name} | {row['convert']:.3f} | {row['build']:.3f} |")


if __name__ == "__main__":
    main()
