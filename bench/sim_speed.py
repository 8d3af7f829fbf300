"""Simulation speed of default builds side by side with hand-tuned models of the same robots.

    python bench/sim_speed.py [--robots go1,g1] [--steps 2000]

The hand-tuned models come from the ``mjlab`` wheel's asset zoo (Unitree go1 and g1, derived
from MuJoCo Menagerie), downloaded into the robot cache like example-robot-data, never into
this repository. Each model stands on a floor: mjcfbuild's from its ``home`` keyframe in its own
scene, the hand-tuned one at its own initial pose in a scene with the same floor. Both hold
their initial ``ctrl`` (the hand-tuned models have no actuators) for ``--steps`` steps after
settling for 0.5 s; the table gives steps per second (best of 5, the two models taking turns)
and contacts at rest.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import mujoco

import mjcfbuild
from bench import robot_data

MJLAB = "mjlab==1.6.0"
HAND_TUNED = {
    "go1": "mjlab/asset_zoo/robots/unitree_go1/xmls/go1.xml",
    "g1": "mjlab/asset_zoo/robots/unitree_g1/xmls/g1.xml",
}
FLOOR_SCENE = """<mujoco model="{name} hand-tuned scene">
  <include file="{model}"/>
  <worldbody><geom name="floor" size="0 0 0.05" type="plane"/></worldbody>
</mujoco>
"""


def hand_tuned_model(name: str, scratch: Path) -> Path:
    """A scene with the mjlab asset zoo's model of ``name`` on a floor."""
    folder = robot_data.cache_dir() / "mjlab"
    wheels = sorted(folder.glob("mjlab-*.whl"))
    if not wheels:
        folder.mkdir(parents=True, exist_ok=True)
        subprocess.run(
            [sys.executable, "-m", "pip", "download", "--no-deps", "-q", MJLAB, "-d", str(folder)],
            check=True,
        )
        wheels = sorted(folder.glob("mjlab-*.whl"))
    top = str(Path(HAND_TUNED[name]).parent.parent) + "/"
    with zipfile.ZipFile(wheels[-1]) as archive:
        for member in archive.namelist():
            if member.startswith(top) and not member.endswith("/"):
                archive.extract(member, folder)
    model = folder / HAND_TUNED[name]
    scene = model.parent / f"bench_scene_{name}.xml"
    scene.write_text(FLOOR_SCENE.format(name=name, model=model.name))
    return scene


def built_model(name: str, scratch: Path) -> Path:
    """mjcfbuild's default build of ``name`` (a bare robot.yaml); its scene."""
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    manifest = robot_data.manifest(robot, scratch / name, urdf, robot_data.package_root())
    return mjcfbuild.build(manifest, jobs=2).scene


def measure(scenes: list[Path], steps: int, rounds: int = 5) -> list[dict]:
    """Steps per second (best of ``rounds``, the models taking turns so both see the same
    machine load) and contacts at rest of the model in each scene."""
    models = [mujoco.MjModel.from_xml_path(str(scene)) for scene in scenes]
    results = [{"steps_per_second": 0.0, "contacts": 0} for _ in models]
    for _ in range(rounds):
        for model, result in zip(models, results, strict=True):
            data = mujoco.MjData(model)
            home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
            if home >= 0:
                mujoco.mj_resetDataKeyframe(model, data, home)
            for _ in range(int(0.5 / model.opt.timestep)):
                mujoco.mj_step(model, data)
            result["contacts"] = data.ncon
            started = time.perf_counter()
            for _ in range(steps):
                mujoco.mj_step(model, data)
            speed = steps / (time.perf_counter() - started)
            result["steps_per_second"] = max(result["steps_per_second"], speed)
    return results


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="go1,g1")
    parser.add_argument("--steps", type=int, default=2000)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        os.environ.setdefault("MJCFBUILD_CACHE_DIR", str(Path(scratch) / "cache"))
        for name in args.robots.split(","):
            scenes = [built_model(name, Path(scratch)), hand_tuned_model(name, Path(scratch))]
            ours, theirs = measure(scenes, args.steps)
            rows.append((name, ours, theirs))
            print(f"measured {name}", file=sys.stderr)
    print(
        "| robot | mjcfbuild default (steps/s) | hand-tuned, mjlab (steps/s) | ratio "
        "| contacts at rest: mjcfbuild | hand-tuned |"
    )
    print("|---|---:|---:|---:|---:|---:|")
    for name, ours, theirs in rows:
        ratio = ours["steps_per_second"] / theirs["steps_per_second"]
        print(
            f"| {name} | {ours['steps_per_second']:.0f} | {theirs['steps_per_second']:.0f} "
            f"| {ratio:.2f} | {ours['contacts']} | {theirs['contacts']} |"
        )


if __name__ == "__main__":
    main()
