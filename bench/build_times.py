"""Build times of mjcfbuild: cold, no-op, and after one mesh changed, printed as a table.

    python bench/build_times.py [--robots panda,g1,go1] [--jobs 2] [--repeat 5]

Each robot is copied into a temporary folder (so a mesh can be edited) and built with the
``mjcfbuild`` command line, timed from the outside as a user would see it. The reference
converter's times are the figures measured for the field guide (it rebuilds everything on every
run, so its no-op time is its cold time).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench import robot_data

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "arm"
# Reference converter, cold build with default settings (GUIDE section 1).
REFERENCE_COLD = {"example arm": None, "panda": 4.0, "go1": 14.0, "g1": None}


def run_build(manifest: Path, jobs: int, env: dict) -> float:
    """Wall-clock seconds of one ``mjcfbuild build`` (fails loudly if the build fails)."""
    started = time.perf_counter()
    process = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", "build", str(manifest), "-q", "-j", str(jobs)],
        capture_output=True,
        text=True,
        env=env,
    )
    seconds = time.perf_counter() - started
    if process.returncode != 0:
        raise SystemExit(f"build of {manifest} failed:\n{process.stderr}")
    return seconds


def nudge_mesh(path: Path) -> None:
    """Change one vertex coordinate of a mesh file slightly, in its own format."""
    data = path.read_bytes()
    suffix = path.suffix.lower()
    binary_stl = len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]
    if suffix == ".stl" and binary_stl:
        x = struct.unpack_from("<f", data, 84 + 12)[0]
        path.write_bytes(data[: 84 + 12] + struct.pack("<f", x + 1e-4) + data[84 + 16 :])
    elif suffix == ".dae":
        match = re.search(rb"(<float_array[^>]*>\s*)(-?[0-9.eE+-]+)", data)
        value = float(match.group(2)) + 1e-4
        path.write_bytes(data[: match.start(2)] + repr(value).encode() + data[match.end(2) :])
    else:  # OBJ and ASCII STL: the first coordinate of the first vertex line
        match = re.search(rb"(\n\s*(?:v|vertex)\s+)(-?[0-9.eE+-]+)", data)
        value = float(match.group(2)) + 1e-4
        path.write_bytes(data[: match.start(2)] + repr(value).encode() + data[match.end(2) :])


def case_example(folder: Path) -> tuple[Path, Path, int]:
    """The example arm: its manifest, a mesh to edit, and its mesh count."""
    target = folder / "arm"
    shutil.copytree(EXAMPLE, target, ignore=shutil.ignore_patterns("mjcf"))
    meshes = [p for p in (target / "meshes").iterdir() if p.suffix != ".mtl"]
    return target / "robot.yaml", target / "meshes" / "upper_arm.dae", len(meshes)


def case_robot(name: str, folder: Path) -> tuple[Path, Path, int]:
    """A robot of example-robot-data: its manifest, a mesh to edit, its mesh count."""
    robot = robot_data.ROBOTS[name]
    urdf, packages = robot_data.copy_robot(robot, folder)
    manifest = robot_data.manifest(robot, folder, urdf, packages)
    text = urdf.read_text(errors="replace")
    files = sorted(set(re.findall(r'filename="package://example-robot-data/([^"]+)"', text)))
    return manifest, packages / files[0], len(files)


def measure(label: str, manifest: Path, mesh: Path, meshes: int, jobs: int, repeat: int) -> dict:
    """Cold, no-op and one-mesh-changed times of one robot."""
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as cache:
        env["MJCFBUILD_CACHE_DIR"] = cache  # a cold build must not reuse cached meshes
        shutil.rmtree(manifest.parent / "mjcf", ignore_errors=True)
        cold = run_build(manifest, jobs, env)
        time.sleep(2.1)  # let the hash cache trust the fresh files' timestamps
        run_build(manifest, jobs, env)
        noop = statistics.median(run_build(manifest, jobs, env) for _ in range(repeat))
        nudge_mesh(mesh)
        changed = run_build(manifest, jobs, env)
    return {
        "robot": label,
        "meshes": meshes,
        "cold": cold,
        "noop": noop,
        "changed": changed,
        "reference": REFERENCE_COLD.get(label),
    }


def print_table(rows: list[dict], jobs: int) -> None:
    """The results as a Markdown table."""
    print(f"\nmjcfbuild build times, -j {jobs}, wall clock in seconds\n")
    print(
        "| robot | mesh files | cold | no-op | one mesh changed | reference converter (every run) |"
    )
    print("|---|---:|---:|---:|---:|---:|")
    for row in rows:
        reference = f"~{row['reference']:.0f}" if row["reference"] else "n/a"
        print(
            f"| {row['robot']} | {row['meshes']} | {row['cold']:.2f} | {row['noop']:.3f} | "
            f"{row['changed']:.2f} | {reference} |"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="panda,g1,go1", help="example-robot-data robots")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=5, help="no-op runs (median)")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        manifest, mesh, count = case_example(scratch / "example")
        rows.append(measure("example arm", manifest, mesh, count, args.jobs, args.repeat))
        for name in [n for n in args.robots.split(",") if n]:
            manifest, mesh, count = case_robot(name, scratch / name)
            rows.append(measure(name, manifest, mesh, count, args.jobs, args.repeat))
            print(f"measured {name}", file=sys.stderr)
    print_table(rows, args.jobs)


if __name__ == "__main__":
    main()
