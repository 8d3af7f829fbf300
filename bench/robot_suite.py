"""The real-robot suite as a table: every robot of example-robot-data the project promises.

    python bench/robot_suite.py [--robots panda,go1,...] [--wheels]

``--wheels`` adds the robots of the other description wheels on PyPI (bench/other_wheels.py);
``--robots`` takes names from either registry.

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
from bench import other_wheels, robot_data
from mjcfbuild.check.kinematics import compare_kinematics
from mjcfbuild.check.results import CheckResults, to_plain
from mjcfbuild.errors import BuildFailed, MjcfbuildError
from mjcfbuild.urdf.parse import parse_urdf


def check(name: str, folder: Path) -> dict:
    """Build and check one robot."""
    robot: robot_data.Robot | other_wheels.WheelRobot
    if name in other_wheels.ROBOTS:
        robot = other_wheels.ROBOTS[name]
        urdf = other_wheels.unpack(robot)
        manifest = other_wheels.manifest(robot, folder, urdf)
        text = other_wheels.urdf_text(robot)
    else:
        robot = robot_data.ALL_ROBOTS[name]
        urdf = robot_data.unpack(robot)
        manifest = robot_data.manifest(robot, folder, urdf, robot_data.package_root())
        text = urdf.read_bytes()
    started = time.perf_counter()
    error = ""
    try:
        result = mjcfbuild.build(manifest, jobs=2)
    except BuildFailed as failed:  # a failed check: the table says which
        result = None
        error = str(failed)
    except MjcfbuildError as failed:  # the description refused: the row says why
        return {"robot": name, "error": str(failed), "seconds": time.perf_counter() - started}
    seconds = time.perf_counter() - started
    checked = CheckResults.read(folder / "mjcf/.mjcfbuild/check.json")
    if checked is None:
        return {"robot": name, "error": error, "seconds": seconds}
    assembly = json.loads((folder / "mjcf/.mjcfbuild/assembly.json").read_text())
    if result is None:
        result = mjcfbuild.build(manifest, jobs=2, check=False)
    model = mujoco.MjModel.from_xml_path(str(result.scene))
    data = mujoco.MjData(model)
    for _ in range(2000):
        mujoco.mj_step(model, data)
    finite = bool(np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel)))
    source = parse_urdf(text, str(urdf))
    kinematics = compare_kinematics(source, mujoco.MjModel.from_xml_path(str(result.robot)))
    repairs = len(assembly.get("repairs") or [])  # the inertia repairs the assembly made
    menagerie = checked.menagerie_test
    fastest = checked.speeds.fastest if checked.speeds else None
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
        "actuators": checked.actuation.actuators if checked.actuation else 0,
        "home": bool(checked.home),
        "floor_gap": checked.floor.gap if checked.floor else None,
        "hold": to_plain(checked.hold) or {},
        "menagerie": to_plain(checked.menagerie_test) or {},
        "touching": len(checked.resting_contacts.pairs) if checked.resting_contacts else 0,
        "failures": checked.failures,
        "passes": finite and kinematics.passes() and checked.passes,
        "floating": robot.floating,
        "driven": not (checked.actuation and checked.actuation.problems),
        "home_sources": sorted({h["source"] for h in assembly["readiness"].get("home", [])}),
        "stand": to_plain(checked.stand),
        "needs_controller": checked.needs_controller,
        "speed": to_plain(fastest)
        or {
            "joint": menagerie.fastest_joint if menagerie else None,
            "speed": menagerie.fastest_speed if menagerie else None,
        },
        "plausibility": to_plain(checked.plausibility),
        "error": error,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", help="comma-separated names (default: all of the wheel)")
    parser.add_argument(
        "--wheels", action="store_true", help="add the robots of bench/other_wheels.py"
    )
    args = parser.parse_args()
    names = args.robots.split(",") if args.robots else sorted(robot_data.ALL_ROBOTS)
    if args.wheels:
        names += [name for name in other_wheels.ROBOTS if name not in names]
    unknown = [n for n in names if n not in robot_data.ALL_ROBOTS and n not in other_wheels.ROBOTS]
    if unknown:
        parser.error(f"unknown robots: {', '.join(unknown)}")
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        os.environ["MJCFBUILD_CACHE_DIR"] = str(Path(scratch) / "cache")
        for name in names:
            rows.append(check(name, Path(scratch) / name))
            print(f"checked {name}", file=sys.stderr)
    print(
        "| robot | links | moving joints | cold build (s) | 2,000 steps finite "
        "| max link position error (m) | max link rotation error (rad) | inertia repairs "
        "| actuators | every joint driven | home from | stands (5 s) | hold error (rad/m) "
        "| fastest joint under the model test (rad/s) | Menagerie test | passes |"
    )
    print("|---|---:|---:|---:|---|---:|---:|---:|---:|---|---|---|---:|---|---|---|")
    for r in rows:
        if "links" not in r:
            print(
                f"| {r['robot']} | | | {r['seconds']:.1f} | | | | | | | | | | | | "
                f"refused: {r['error']} |"
            )
            continue
        print(
            f"| {r['robot']} | {r['links']} | {r['joints']} | {r['seconds']:.1f} "
            f"| {'yes' if r['finite'] else 'NO'} | {r['position']:.1e} | {r['rotation']:.1e} "
            f"| {r['repairs']} | {r['actuators']} | {'yes' if r['driven'] else 'NO'} "
            f"| {', '.join(r['home_sources']) or '-'} | {_stands(r)} "
            f"| {r['hold'].get('max_deviation', 0):.3f} | {_speed(r['speed'])} "
            f"| {_menagerie(r['menagerie'])} | {'yes' if r['passes'] else 'NO: ' + _first(r)} |"
        )
    for r in rows:
        for failure in r.get("failures", []):
            print(f"{r['robot']}: {failure}", file=sys.stderr)


def _stands(row: dict) -> str:
    if not row["floating"]:
        return "fixed base"
    if row["needs_controller"]:
        return f"needs a controller: {row['needs_controller']}"
    stand = row["stand"] or {}
    if not stand:
        return "-"
    fell = stand["max_tilt"] > 0.2 or stand["max_sink"] > 0.1 * stand["home_height"] + 0.01
    return f"{'NO' if fell else 'yes'} (tilt {stand['max_tilt']:.2f} rad)"


def _speed(speed: dict) -> str:
    if not speed or speed.get("speed") is None:
        return "-"
    limit = f" (limit {speed['limit']:.3g})" if speed.get("limit") else ""
    return f"{speed['speed']:.3g} {speed.get('joint')}{limit}"


def _menagerie(menagerie: dict) -> str:
    return "pass" if menagerie.get("finite") and not menagerie.get("warnings") else "FAIL"


def _first(row: dict) -> str:
    failures = row.get("failures") or [row.get("error") or "kinematics or simulation"]
    return failures[0].replace("|", "/")


if __name__ == "__main__":
    main()
