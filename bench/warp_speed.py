"""MuJoCo Warp throughput of the full model, the training variant and a hand-tuned model.

    python bench/warp_speed.py [--robots go1,g1,panda] [--worlds 512] [--steps 50] [--device cpu]

Each robot is built from a bare robot.yaml with ``output.training: true``. The hand-tuned
training models are mjlab's asset zoo (go1, g1; from the mjlab wheel on PyPI, unpacked into
the robot cache, never into this repository). mjlab's XML files have no actuators and no
keyframe (mjlab adds them from Python), so they are given here what its constants say: the
home pose (``HOME_KEYFRAME`` / ``INIT_STATE``), a position actuator and the reflected rotor
inertia (armature) on every hinge, the implicitfast integrator, and two
collision set-ups from its constants, as shipped (every capsule against every other) and
``FEET_ONLY_COLLISION``; they run with the variant's solver settings, so what differs is the
model. Every scene is stepped the same way (``mjcfbuild.check.warp_variant.measure``): the
same worlds, steps and noise on ``ctrl``, in one run, best of ``--rounds`` with the models
taking turns (the machine is shared); the variant's behaviour at home (5 s
standing, or 1 s holding) is checked in Warp too.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import mjcfbuild
from bench import robot_data
from bench.sim_speed import hand_tuned_model
from mjcfbuild.check.warp_variant import behaviour, measure

# mjlab 1.6.0's constants (asset_zoo/robots/unitree_*/..._constants.py): base height, joint
# angles by pattern, and position gains (go1's from its rotor inertia at 10 Hz; g1's a
# round figure between its motors').
MJLAB_HOME = {
    "go1": (
        0.278,
        {
            r".*thigh_joint": 0.9,
            r".*calf_joint": -1.8,
            r".*R_hip_joint": 0.1,
            r".*L_hip_joint": -0.1,
        },
    ),
    "g1": (
        0.783675,
        {
            r".*_hip_pitch_joint": -0.1,
            r".*_knee_joint": 0.3,
            r".*_ankle_pitch_joint": -0.2,
            r".*_shoulder_pitch_joint": 0.2,
            r".*_elbow_joint": 1.28,
            r"left_shoulder_roll_joint": 0.2,
            r"right_shoulder_roll_joint": -0.2,
        },
    ),
}
MJLAB_KP = {"go1": 40.0, "g1": 100.0}
# Rotor inertia reflected through the gearbox, which mjlab sets per actuator from Python
# (go1: 0.000111842 x 6^2 to x 9^2; g1's motors 0.01 to 0.03): without it the light joints
# under these gains go unstable within 0.02 s, and a diverged simulation is no benchmark.
MJLAB_ARMATURE = {"go1": 0.005, "g1": 0.02}
MJLAB_FEET = {"go1": r"^[FR][LR]_foot_collision$", "g1": r"^(left|right)_foot[1-7]_collision$"}


def built(name: str, scratch: Path) -> tuple[Path, Path]:
    """The full scene and the variant's scene of ``name`` built from a bare robot.yaml."""
    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    extra = "output:\n  training: true\n"
    manifest = robot_data.manifest(robot, scratch / name, urdf, robot_data.package_root(), extra)
    result = mjcfbuild.build(manifest, jobs=2, check=False)
    return result.scene, result.scene.parent / "scene_mjx.xml"


def mjlab_scene(name: str, scratch: Path, feet_only: bool, iterations: int, ls: int) -> Path:
    """mjlab's model of ``name`` on a floor, with home, actuators and solver settings."""
    import mujoco

    shipped = hand_tuned_model(name, scratch)  # a scene that includes the zoo's XML
    model_file = shipped.parent / f"{name}.xml"
    spec = mujoco.MjSpec.from_file(str(model_file))
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05])
    height, angles = MJLAB_HOME[name]
    model = spec.compile()
    qpos = model.qpos0.copy()
    qpos[2] = height
    for joint in spec.joints:
        if joint.type != mujoco.mjtJoint.mjJNT_HINGE:
            continue
        angle = next((a for p, a in angles.items() if re.fullmatch(p, joint.name)), 0.0)
        qpos[model.joint(joint.name).qposadr[0]] = angle
        joint.armature = MJLAB_ARMATURE[name]
        actuator = spec.add_actuator(name=joint.name, target=joint.name)
        actuator.trntype = mujoco.mjtTrn.mjTRN_JOINT
        actuator.set_to_position(kp=MJLAB_KP[name], kv=MJLAB_KP[name] / 20)
    model = spec.compile()
    ctrl = [qpos[model.jnt_qposadr[model.actuator_trnid[a, 0]]] for a in range(model.nu)]
    spec.add_key(name="home", qpos=list(qpos), ctrl=ctrl)
    if feet_only:
        for geom in spec.geoms:
            if geom.name != "floor" and (geom.contype or geom.conaffinity):
                on_floor = bool(re.match(MJLAB_FEET[name], geom.name or ""))
                geom.contype, geom.conaffinity = 0, int(on_floor)
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST  # mjlab's, and ours
    spec.option.iterations = iterations
    spec.option.ls_iterations = ls
    path = model_file.parent / f"bench_warp_{name}_{'feet' if feet_only else 'shipped'}.xml"
    path.write_text(spec.to_xml())
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="go1,g1,panda")
    parser.add_argument("--worlds", type=int, default=512)
    parser.add_argument("--steps", type=int, default=50)
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--rounds", type=int, default=2, help="best of this many runs each")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        os.environ.setdefault("MJCFBUILD_CACHE_DIR", str(Path(scratch) / "cache"))
        for name in args.robots.split(","):
            full, variant = built(name, Path(scratch))
            import mujoco

            solver = mujoco.MjModel.from_xml_path(str(variant)).opt
            scenes = [("full model", full), ("training variant", variant)]
            if name in MJLAB_HOME:
                for feet_only, label in ((False, "mjlab, as shipped"), (True, "mjlab, feet only")):
                    path = mjlab_scene(
                        name, Path(scratch), feet_only, solver.iterations, solver.ls_iterations
                    )
                    scenes.append((label, path))
            figures: dict = {}
            for _ in range(args.rounds):  # best of rounds, the models taking turns
                for label, path in scenes:
                    result = measure(str(path), args.worlds, args.steps, device=args.device)
                    best = figures.get(label)
                    if best is None or result.steps_per_second > best.steps_per_second:
                        figures[label] = result
            line, failure = behaviour(str(variant), 0.05, args.device)
            rows.append((name, figures, line + (f" (FAILS: {failure})" if failure else "")))
            print(f"measured {name}", file=sys.stderr)
    print(
        f"MuJoCo Warp on {args.device}: {args.worlds} worlds, {args.steps} steps, noise on ctrl\n"
    )
    print("| robot | model | collision geoms | contact pairs | finite | steps/s | vs full |")
    print("|---|---|---:|---:|---|---:|---:|")
    for name, figures, _ in rows:
        base = figures["full model"].steps_per_second
        for label, result in figures.items():
            ratio = result.steps_per_second / base if base else 0.0
            print(
                f"| {name} | {label} | {result.collision_geoms} | {result.contact_pairs} "
                f"| {'yes' if result.finite else 'NO'} | {result.steps_per_second:.0f} "
                f"| {ratio:.2f}x |"
            )
    print()
    for name, _, line in rows:
        print(f"- {name} variant in Warp: {line}")


if __name__ == "__main__":
    main()
