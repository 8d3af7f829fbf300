"""Where users wait: cold, no-op (fast and full path), one mesh or one joint attribute changed.

    python bench/edit_times.py [--robots panda,go1] [--repeat 5] [--jobs 2]

Each robot is copied into a temporary folder and built with the ``mjcfbuild`` command line
(check and previews included), timed from the outside as a user would see it, with a fresh
cache folder. The no-op is timed twice: as ``mjcfbuild build`` runs it (the stamp fast path)
and with ``MJCFBUILD_FULL_BUILD=1`` (the full doit graph). The joint edit changes the damping
of the first joint of the URDF (or xacro), the mesh edit one vertex of one mesh. The reference
converter rebuilds everything on every run; its figures are the ones recorded on this machine
(issue 14) unless ``--reference`` names a live command to time.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench.build_times import case_example, case_robot, nudge_mesh

# The reference converter's full run, measured on this 2-core machine (issue 14).
REFERENCE_RECORDED = {"panda": 5.4, "go1": 14.6}


def timed_build(manifest: Path, jobs: int, env: dict) -> tuple[float, str]:
    """Wall-clock seconds of one ``mjcfbuild build`` and its summary line."""
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", "build", str(manifest), "-j", str(jobs)],
        capture_output=True,
        text=True,
        env=env,
    )
    seconds = time.perf_counter() - started
    if done.returncode != 0:
        raise SystemExit(f"build of {manifest} failed:\n{done.stderr}")
    summary = [line for line in done.stdout.splitlines() if line.startswith("mjcfbuild:")]
    return seconds, (summary[-1] if summary else "")


def edit_joint(manifest: Path) -> Path:
    """Change (or add) the damping of the first joint with dynamics; the file edited."""
    text = manifest.read_text()
    match = re.search(r"(?:urdf|xacro): (\S+)", text)
    source = (manifest.parent / match.group(1)).resolve()
    xml = source.read_text()
    found = re.search(r'damping="([0-9.eE+-]+)"', xml)
    if found:
        value = float(found.group(1)) + 0.01
        xml = xml[: found.start(1)] + repr(value) + xml[found.end(1) :]
    else:  # no damping anywhere: give the first revolute joint some
        joint = re.search(r'<joint[^>]*type="(?:revolute|continuous)"[^>]*>', xml)
        xml = xml[: joint.end()] + '<dynamics damping="0.01"/>' + xml[joint.end() :]
    source.write_text(xml)
    return source


def measure(label: str, manifest: Path, mesh: Path, repeat: int, jobs: int) -> dict:
    """The times of one robot (seconds) and which tasks ran after each edit."""
    env = dict(os.environ)
    full = {**env, "MJCFBUILD_FULL_BUILD": "1"}
    row: dict = {"robot": label}
    with tempfile.TemporaryDirectory() as cache:
        env["MJCFBUILD_CACHE_DIR"] = full["MJCFBUILD_CACHE_DIR"] = cache
        row["cold"], _ = timed_build(manifest, jobs, env)
        time.sleep(2.1)  # past the racy window: the fast path trusts mtimes from here on
        timed_build(manifest, jobs, env)  # refreshes the stamp of files written in the window
        row["noop"] = statistics.median(timed_build(manifest, jobs, env)[0] for _ in range(repeat))
        row["noop_full"] = statistics.median(
            timed_build(manifest, jobs, full)[0] for _ in range(repeat)
        )
        nudge_mesh(mesh)
        row["mesh"], row["mesh_summary"] = timed_build(manifest, jobs, env)
        edit_joint(manifest)
        row["joint"], row["joint_summary"] = timed_build(manifest, jobs, env)
    row["reference"] = REFERENCE_RECORDED.get(label)
    return row


def print_table(rows: list[dict], jobs: int) -> None:
    """The results as a Markdown table."""
    print(f"\nmjcfbuild build times, wall clock in seconds, -j {jobs}, check and previews on\n")
    print(
        "| robot | cold | no-op | no-op, full graph | one mesh changed | one joint damping "
        "changed | reference converter (every run, recorded) |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        reference = f"{row['reference']:.1f}" if row["reference"] else "n/a"
        print(
            f"| {row['robot']} | {row['cold']:.2f} | {row['noop']:.3f} | {row['noop_full']:.3f} "
            f"| {row['mesh']:.2f} | {row['joint']:.2f} | {reference} |"
        )
    print()
    for row in rows:
        print(f"- {row['robot']}, one mesh changed: {row['mesh_summary']}")
        print(f"- {row['robot']}, one joint damping changed: {row['joint_summary']}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="panda,go1", help="example-robot-data robots")
    parser.add_argument("--repeat", type=int, default=5, help="no-op runs (median)")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        manifest, mesh, _ = case_example(folder / "example")
        rows.append(measure("example arm", manifest, mesh, args.repeat, args.jobs))
        for name in [n for n in args.robots.split(",") if n]:
            manifest, mesh, _ = case_robot(name, folder / name)
            rows.append(measure(name, manifest, mesh, args.repeat, args.jobs))
            print(f"measured {name}", file=sys.stderr)
        shutil.rmtree(folder, ignore_errors=True)
    print_table(rows, args.jobs)


if __name__ == "__main__":
    main()
