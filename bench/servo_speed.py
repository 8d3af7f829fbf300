"""Simulation speed of the default servo (a <dcmotor> with the URDF's torque-speed line)
against plain <position> servos on the legged robots of example-robot-data.

    python bench/servo_speed.py [--robots go1,g1,...] [--steps 2000]

mujoco_ros2_control takes a <dcmotor> for a custom actuator (its bias is not affine) and
commands position only on <position> servos, so joints a <ros2_control> block commands get
<position> servos. This measures what the choice costs or gains in simulation for robots without
such a block: each robot is built twice from a bare robot.yaml, once as it is and once with
``actuators: {speed_limits: false}`` (<position> servos, same gains and force limits), and both
hold home's ctrl on the floor (steps per second, best of 5, the two models taking turns); the
stand column is the build's own 5 s stand test (base tilt in rad).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import mjcfbuild
from bench import robot_data
from bench.sim_speed import measure
from mjcfbuild.check.results import CheckResults

LEGGED = "go1,go2,a1,anymal_c,solo12,g1,talos"
POSITION_SERVOS = "actuators:\n  speed_limits: false\n"


def build(name: str, folder: Path, extra: str) -> tuple[Path, CheckResults]:
    """The scene of ``name`` built with ``extra`` in its robot.yaml, and its check record."""
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(robot, folder, urdf, robot_data.package_root(), extra)
    scene = mjcfbuild.build(manifest, jobs=2).scene
    return scene, CheckResults.read(folder / "mjcf/.mjcfbuild/check.json") or CheckResults()


def tilt(check: CheckResults) -> str:
    """The stand test's largest base tilt, or why it was not run."""
    if check.stand is None:
        return "-"
    if check.stand_verdict() == "needs a controller":
        return "needs a controller"
    return f"{check.stand.max_tilt:.3f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default=LEGGED)
    parser.add_argument("--steps", type=int, default=2000)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        os.environ.setdefault("MJCFBUILD_CACHE_DIR", str(Path(scratch) / "cache"))
        for name in args.robots.split(","):
            dcmotor, dc_check = build(name, Path(scratch) / name / "dcmotor", "")
            position, pos_check = build(name, Path(scratch) / name / "position", POSITION_SERVOS)
            ours, plain = measure([dcmotor, position], args.steps)
            rows.append((name, ours, plain, tilt(dc_check), tilt(pos_check)))
            print(f"measured {name}", file=sys.stderr)
    print(
        "| robot | <dcmotor> default (steps/s) | <position> (steps/s) | ratio "
        "| stand tilt: <dcmotor> | <position> |"
    )
    print("|---|---:|---:|---:|---:|---:|")
    for name, ours, plain, dc_tilt, pos_tilt in rows:
        ratio = ours["steps_per_second"] / plain["steps_per_second"]
        print(
            f"| {name} | {ours['steps_per_second']:.0f} | {plain['steps_per_second']:.0f} "
            f"| {ratio:.2f} | {dc_tilt} | {pos_tilt} |"
        )


if __name__ == "__main__":
    main()
