"""g1 with every collision mesh decomposed, cold, at -j 1 and -j 2, printed as tables.

    python bench/decompose.py [--robot g1] [--jobs 1,2]

Each run builds a fresh copy of the robot with ``collision: {default: decompose}`` and an
empty product cache, timed from the outside as a user would see it, while the peak memory of
the build and its worker processes (the sum of their resident sets, sampled every 0.1 s) is
recorded. Per mesh it prints whether the hull was kept or CoACD ran, the parts, the concavity
reached (how far the parts stand off the mesh, in CoACD's units) and the seconds; then it checks
that every decomposed mesh is in the model with all its parts and that the model simulates to
finite values. A cold build with ``collision: {default: hull}`` at the same -j gives the time
that is not decomposition, so the -j speed-up on decomposition can be read apart.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import resource
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench import robot_data


def build(manifest: Path, jobs: int, cache: Path) -> dict:
    """One cold ``mjcfbuild build``: wall seconds, CPU seconds, peak memory of the tree."""
    env = dict(os.environ, MJCFBUILD_CACHE_DIR=str(cache))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    process = subprocess.Popen(
        [sys.executable, "-m", "mjcfbuild", "build", str(manifest), "-q", "-j", str(jobs)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    peak = PeakMemory(process.pid)
    peak.start()
    stdout, stderr = process.communicate()
    seconds = time.perf_counter() - started
    peak.stop()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if process.returncode != 0:
        raise SystemExit(f"build of {manifest} failed:\n{stdout}\n{stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {
        "seconds": seconds,
        "cpu": cpu,
        "peak_mb": peak.peak / 1e6,
    }


class PeakMemory(threading.Thread):
    """The largest sum of resident memory of a process and its descendants, sampled."""

    def __init__(self, pid: int) -> None:
        super().__init__(daemon=True)
        self.pid = pid
        self.peak = 0
        self._done = threading.Event()

    def run(self) -> None:
        import psutil

        try:
            root = psutil.Process(self.pid)
        except psutil.NoSuchProcess:
            return
        while not self._done.is_set():
            total = 0
            try:
                for process in [root, *root.children(recursive=True)]:
                    with contextlib.suppress(psutil.NoSuchProcess):
                        total += process.memory_info().rss
            except psutil.NoSuchProcess:
                return
            self.peak = max(self.peak, total)
            self._done.wait(0.1)

    def stop(self) -> None:
        self._done.set()
        self.join()


def robot_copy(name: str, folder: Path, policy: str) -> Path:
    """A manifest building the robot with one collision policy for every mesh."""
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    extra = f"collision: {{default: {policy}}}\ncheck: {{enabled: false}}\n"
    return robot_data.manifest(robot, folder, urdf, robot_data.package_root(), extra)


def decompositions(manifest: Path) -> dict[str, dict]:
    """The decomposition summaries the build wrote, by name."""
    folder = manifest.parent / "mjcf" / ".mjcfbuild" / "decompositions"
    return {p.stem: json.loads(p.read_text()) for p in sorted(folder.glob("*.json"))}


def model_check(manifest: Path, summaries: dict[str, dict]) -> dict:
    """Every decomposition in the model with all its parts as collision geoms; the scene
    simulated for 2 s (zero control) stays finite."""
    import mujoco
    import numpy as np

    folder = manifest.parent / "mjcf"
    model = mujoco.MjModel.from_xml_path(str(next(folder.glob("scene.xml"))))
    counts: dict[str, int] = {}
    for geom in range(model.ngeom):
        if model.geom_type[geom] != mujoco.mjtGeom.mjGEOM_MESH:
            continue
        if model.geom_contype[geom] == 0 and model.geom_conaffinity[geom] == 0:
            continue
        mesh = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_MESH, model.geom_dataid[geom])
        name = mesh.rsplit("_part", 1)[0]
        counts[name] = counts.get(name, 0) + 1
    missing = [n for n, s in summaries.items() if counts.get(n, 0) != len(s["parts"])]
    data = mujoco.MjData(model)
    mujoco.mj_resetData(model, data)
    finite = True
    for _ in range(int(2.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
        if not (np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))):
            finite = False
            break
    return {"missing": missing, "finite": finite, "collision_geoms": sum(counts.values())}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robot", default="g1", help="an example-robot-data robot")
    parser.add_argument("--jobs", default="1,2", help="job counts to compare")
    args = parser.parse_args()
    runs = {}
    with tempfile.TemporaryDirectory() as scratch:
        root = Path(scratch)
        for jobs in [int(j) for j in args.jobs.split(",")]:
            load = os.getloadavg()[0]
            hull_manifest = robot_copy(args.robot, root / f"hull-j{jobs}", "hull")
            hull = build(hull_manifest, jobs, root / f"hull-cache-j{jobs}")
            manifest = robot_copy(args.robot, root / f"decompose-j{jobs}", "decompose")
            result = build(manifest, jobs, root / f"cache-j{jobs}")
            result["load_before"] = load
            result["load_after"] = os.getloadavg()[0]
            result["hull_seconds"] = hull["seconds"]
            result["summaries"] = decompositions(manifest)
            result["check"] = model_check(manifest, result["summaries"])
            runs[jobs] = result
            print(f"measured -j {jobs}: {result['seconds']:.1f} s", file=sys.stderr)
    print_tables(args.robot, runs)


def print_tables(robot: str, runs: dict[int, dict]) -> None:
    """The results as Markdown tables."""
    print(f"\n{robot}, `collision: {{default: decompose}}`, cold (empty cache), wall clock\n")
    print(
        "| -j | build (s) | of which decomposition (s) | build CPU (s) | peak memory, build + "
        "workers (MB) | hulls kept | CoACD runs | parts | "
        "meshes in the model | finite | load average (start, end) |"
    )
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|")
    for jobs, run in runs.items():
        summaries = run["summaries"].values()
        kept = sum(1 for s in summaries if s.get("method") == "hull")
        check = run["check"]
        represented = f"{len(run['summaries']) - len(check['missing'])}/{len(run['summaries'])}"
        print(
            f"| {jobs} | {run['seconds']:.1f} | {run['seconds'] - run['hull_seconds']:.1f} "
            f"| {run['cpu']:.0f} | {run['peak_mb']:.0f} "
            f"| {kept} | {len(run['summaries']) - kept} "
            f"| {sum(len(s['parts']) for s in summaries)} | {represented} "
            f"| {'yes' if check['finite'] else 'NO'} "
            f"| {run['load_before']:.1f}, {run['load_after']:.1f} |"
        )
    if 1 in runs and 2 in runs:
        one, two = runs[1], runs[2]
        speedup = (one["seconds"] - one["hull_seconds"]) / (two["seconds"] - two["hull_seconds"])
        print(f"\n-j 2 against -j 1 on decomposition: {speedup:.2f}x")
    last = runs[max(runs)]
    print(f"\nPer mesh (-j {max(runs)}); concavity in CoACD's units (threshold 0.05)\n")
    print("| mesh | how | parts | hull concavity | concavity reached | seconds |")
    print("|---|---|---:|---:|---:|---:|")
    for name, s in last["summaries"].items():
        how = "hull kept" if s.get("method") == "hull" else "CoACD"
        print(
            f"| {name} | {how} | {len(s['parts'])} | {s['hull_concavity']:.3f} "
            f"| {s['concavity']:.3f} | {s['seconds']:.1f} |"
        )


if __name__ == "__main__":
    main()
