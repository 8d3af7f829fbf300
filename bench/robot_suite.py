"""The real-robot suite as a table: every robot of example-robot-data the project promises.

    python bench/robot_suite.py [--robots panda,go1,...]

For each robot: build with default settings (a fresh cache), load the scene, simulate 2,000
steps with zero control, and compare every URDF link's pose with forward kinematics computed
from the URDF alone at 20 random configurations. The same checks run as tests
(``pytest -m robots``); this prints the numbers for docs/robots.md.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import mujoco
import numpy as np

import mjcfbuild
from bench import robot_data
from mjcfbuild.check.kinematics import compare_kinematics
from mjcfbuild.errors import BuildFailed
from mjcfbuild.urdf.parse import parse_urdf


def check(name: str, folder: Path) -> dict:
    """Build and check one robot."""
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(robot, folder, urdf, robot_data.package_root())
    started = time.perf_counter()
    try:
        result = mjcfbuild.build(manifest, jobs=2)
    except BuildFailed:  # a failed check: the table says which
        result = None
    seconds = time.perf_counter() - started
    checked = json.loads((folder / "mjcf/.mjcfbuild/check.json").read_text())
    if result is None:
        result = mjcfbuild.build(manifest, jobs=2, check=False)
    model = mujoco.MjModel.from_xml_path(str(result.scene))
    data = mujoco.MjData(model)
    for _ in range(2000):
        mujoco.mj_step(model, data)
    finite = bool(np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel)))
    source = parse_urdf(urdf.read_bytes(), str(urdf))
    kinematics = compare_kinematics(source, mujoco.MjModel.from_xml_path(str(result.robot)))
    repairs = sum(1 for w in result.warnings if w.startswith("body '"))
    return {
        "robot": name,
        "links": len(source.links),
        "joints": sum(1 for j in source.joints if j.kind != "fixed"),
        "seconds": seconds,
        "finite": finite,
        "position": kinematics.max_position,
        "rotation": kinematics.max_rotation,
        "missing": len(kinematics.missing_links) + len(kinematics.missing_joints),
        "repairs": repairs,
        "actuators": checked.get("actuation", {}).get("actuators", 0),
        "home": bool(checked.get("home")),
        "floor_gap": checked.get("floor_gap"),
        "hold": checked.get("hold", {}),
        "menagerie": checked.get("menagerie_test", {}),
        "fastest": checked.get("max_joint_speed"),
        "touching": len(checked.get("resting_contacts", {}).get("pairs", [])),
        "failures": checked.get("failures", []),
        "passes": finite and kinematics.passes() and bool(checked.get("passes")),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default=",".join(sorted(robot_data.ROBOTS)))
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        os.environ["MJCFBUILD_CACHE_DIR"] = str(Path(scratch) / "cache")
        for name in args.robots.split(","):
            rows.append(check(name, Path(scratch) / name))
            print(f"checked {name}", file=sys.stderr)
    print(
        "| robot | links | moving joints | cold build (s) | 2,000 steps finite "
        "| max link position error (m) | max link rotation error (rad) | inertia repairs "
        "| actuators | home | bodies touching at home | floor contact at home (mm) "
        "| hold error (rad/m) | Menagerie test | fastest joint under it (speed / limit) | passes |"
    )
    print("|---|---:|---:|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---|---|---|")
    for r in rows:
        gap = f"{r['floor_gap'] * 1000:.2f}" if r["floor_gap"] is not None else "fixed base"
        hold = r["hold"].get("max_deviation")
        tilt = r["hold"].get("base_tilt")
        hold_text = f"{hold:.3f}" + (
            f" (floating; base tilts {tilt:.2f} rad)" if tilt is not None else ""
        )
        menagerie = r["menagerie"]
        test = "pass" if menagerie.get("finite") and not menagerie.get("warnings") else "FAIL"
        fastest = r["fastest"]
        speed = (
            f"{fastest['joint']} {fastest['speed']:.3g} / {fastest['limit']:g}" if fastest else "-"
        )
        print(
            f"| {r['robot']} | {r['links']} | {r['joints']} | {r['seconds']:.1f} "
            f"| {'yes' if r['finite'] else 'NO'} | {r['position']:.1e} | {r['rotation']:.1e} "
            f"| {r['repairs']} | {r['actuators']} | {'yes' if r['home'] else 'no'} "
            f"| {r['touching']} | {gap} | {hold_text} | {test} | {speed} "
            f"| {'yes' if r['passes'] else 'NO'} |"
        )
    for r in rows:
        for failure in r["failures"]:
            print(f"{r['robot']}: {failure}", file=sys.stderr)


if __name__ == "__main__":
    main()
