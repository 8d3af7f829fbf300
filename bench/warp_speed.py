"""MuJoCo Warp throughput of the full model, the training variant and a hand-tuned model.

    python bench/warp_speed.py [--robots go1,g1,panda] [--worlds 512] [--steps 50] [--device cpu]
    python bench/warp_speed.py --export DIR     # build here; write the scenes to measure to DIR
    python bench/warp_speed.py --from DIR --device cuda   # measure them on another machine

Each robot is built from a bare robot.yaml with ``output.training: true``. The hand-tuned
training models are mjlab's asset zoo (go1, g1; from the mjlab wheel on PyPI, unpacked into
the robot cache, never into this repository). mjlab's XML files have no actuators and no
keyframe (mjlab adds them from Python), so they are given here what its constants say: the
home pose (``HOME_KEYFRAME`` / ``INIT_STATE``), a position actuator and the reflected rotor
inertia (armature) on every hinge, the implicitfast integrator, and two
collision set-ups from its constants, as shipped (every capsule against every other) and
``FEET_ONLY_COLLISION``. The variant is built twice, with ``output.training.device`` gpu and
cpu (each device's solver defaults); mjlab's scenes run under each variant's solver settings
in turn, so what differs between a variant and mjlab's models is the model. Every scene is
stepped the same way (``mjcfbuild.check.warp_variant.measure``): the same worlds, steps and
noise on ``ctrl``, in one run, best of ``--rounds`` with the models taking turns (the machine
is shared); each variant's behaviour at home (5 s standing, or 1 s holding) is checked in Warp
too.

``--export DIR`` writes every scene, the files it reads (model, meshes) and ``bench.json``
(what to measure, and how) to ``DIR``, the files packed in ``scenes.tar.xz`` (about 20 MB for
the three robots); ``--from DIR`` measures them on a machine that has only mujoco,
mujoco_warp, warp-lang and numpy (no build dependencies, no network) and prints the same
table with the device's name.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
import tarfile
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

PLAN = "bench.json"
ARCHIVE = "scenes.tar.xz"
HOLD_TOLERANCE = 0.05  # rad: a fixed robot's joints from home in the 1 s hold

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


DEVICES = ("gpu", "cpu")  # output.training.device: a variant with each one's solver defaults


def built(name: str, scratch: Path) -> tuple[Path, dict[str, Path]]:
    """The full scene of ``name`` built from a bare robot.yaml, and the variant's scene built
    for each device (the same build with ``output.training.device`` set)."""
    import mjcfbuild
    from bench import robot_data

    robot = robot_data.ROBOTS[name]
    urdf = robot_data.unpack(robot)
    variants = {}
    for device in DEVICES:
        extra = f"output:\n  training:\n    device: {device}\n"
        folder = scratch / name / device
        manifest = robot_data.manifest(robot, folder, urdf, robot_data.package_root(), extra)
        result = mjcfbuild.build(manifest, jobs=2, check=False)
        variants[device] = result.scene.parent / "scene_mjx.xml"
    return result.scene, variants


def solver_label(scene: str | Path) -> str:
    """The scene's solver and iteration caps, as ``Newton 1/5``."""
    import mujoco

    option = mujoco.MjModel.from_xml_path(str(scene)).opt
    solver = {0: "PGS", 1: "CG", 2: "Newton"}[int(option.solver)]  # mjtSolver's values
    return f"{solver} {option.iterations}/{option.ls_iterations}"


def mjlab_scene(name: str, scratch: Path, feet_only: bool, solver, device: str) -> Path:
    """mjlab's model of ``name`` on a floor, with home, actuators and the solver settings of
    the variant built for ``device``."""
    import mujoco

    from bench.sim_speed import hand_tuned_model

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
    spec.option.solver = solver.solver  # the variant's solver settings: what differs is the model
    spec.option.iterations = solver.iterations
    spec.option.ls_iterations = solver.ls_iterations
    kind = "feet" if feet_only else "shipped"
    path = model_file.parent / f"bench_warp_{name}_{kind}_{device}.xml"
    path.write_text(spec.to_xml())
    return path


def planned(names: list[str], scratch: Path) -> list[dict]:
    """Build each robot and write mjlab's scenes: for each robot, the scenes to measure
    (label, path) and each device's variant scene, whose behaviour is checked."""
    import mujoco

    plan = []
    for name in names:
        full, variants = built(name, scratch)
        scenes = [("full model", full)]
        for device, variant in variants.items():
            scenes.append((f"training variant ({device})", variant))
            if name in MJLAB_HOME:
                solver = mujoco.MjModel.from_xml_path(str(variant)).opt
                for feet_only, label in ((False, "mjlab, as shipped"), (True, "mjlab, feet only")):
                    scene = mjlab_scene(name, scratch, feet_only, solver, device)
                    scenes.append((f"{label} ({device})", scene))
        listed = [[label, str(path)] for label, path in scenes]
        checked = [[device, str(path)] for device, path in variants.items()]
        plan.append({"robot": name, "scenes": listed, "variants": checked})
    return plan


def read_files(scene: Path) -> set[Path]:
    """The files loading ``scene`` reads: itself, the files it includes, and the meshes,
    textures and height fields of the model they make."""
    import mujoco

    found = {scene.resolve()}
    for included in re.findall(r'<include\s+file="([^"]+)"', scene.read_text()):
        found |= read_files(scene.parent / included)
    spec = mujoco.MjSpec.from_file(str(scene))
    for assets, folder in (
        (spec.meshes, spec.meshdir),
        (spec.hfields, ""),
        (spec.textures, spec.texturedir),
    ):
        for asset in assets:
            if asset.file:
                found.add((scene.parent / (folder or "") / asset.file).resolve())
    return found


def _packed(robot: str, scene: str, names: dict, members: dict) -> str:
    """``scene``'s path in the archive (``<robot>/<its folder's name>/<file>``), its folder
    named in ``names`` and the files it reads added to ``members`` (archive name -> path)."""
    path = Path(scene).resolve()
    if path.parent not in names:
        name = f"{robot}/{path.parent.name}"
        while name in names.values():
            name += "_"
        names[path.parent] = name
    root = names[path.parent]
    for read in read_files(path):
        members[f"{root}/{read.relative_to(path.parent)}"] = read
    return f"{root}/{path.name}"


def export(plan: list[dict], folder: Path, settings: dict) -> Path:
    """Write ``plan``'s scenes and every file they read to ``folder``, packed in ARCHIVE,
    with PLAN naming them by their path in the archive; the archive's path."""
    members: dict[str, Path] = {}
    moved = []
    for robot in plan:
        names: dict[Path, str] = {}
        name = robot["robot"]
        scenes = [[label, _packed(name, scene, names, members)] for label, scene in robot["scenes"]]
        variants = [
            [device, _packed(name, path, names, members)] for device, path in robot["variants"]
        ]
        moved.append({"robot": name, "scenes": scenes, "variants": variants})
    folder.mkdir(parents=True, exist_ok=True)
    archive = folder / ARCHIVE
    with tarfile.open(archive, "w:xz") as packed:
        for member, path in sorted(members.items()):
            packed.add(path, arcname=member, recursive=False)
    document = {**settings, "hold_tolerance": HOLD_TOLERANCE, "robots": moved}
    (folder / PLAN).write_text(json.dumps(document, indent=1) + "\n")
    return archive


def unpacked(folder: Path, into: Path) -> tuple[dict, list[dict]]:
    """An exported folder's settings and plan, its scenes unpacked under ``into``."""
    document = json.loads((folder / PLAN).read_text())
    with tarfile.open(folder / ARCHIVE) as packed:
        if hasattr(tarfile, "data_filter"):  # Python 3.12, and 3.8.17+ / 3.11.4+ backports
            packed.extractall(into, filter="data")
        else:
            packed.extractall(into)
    plan = [
        {
            "robot": robot["robot"],
            "scenes": [[label, str(into / scene)] for label, scene in robot["scenes"]],
            "variants": [[device, str(into / path)] for device, path in _variants(robot)],
        }
        for robot in document.pop("robots")
    ]
    return document, plan


def _variants(robot: dict) -> list[list[str]]:
    """An exported robot's variants by device; a folder exported before there were two has
    one ``variant`` (built with CG 2/4, today's cpu settings)."""
    if "variants" in robot:
        return robot["variants"]
    return [["cpu", robot["variant"]]]


def measured(plan: list[dict], worlds: int, steps: int, rounds: int, device: str, hold: float):
    """Every scene of ``plan`` measured (best of ``rounds``, the scenes taking turns) and each
    variant's behaviour: rows of (robot, {label: figures}, {label: solver}, behaviour line)."""
    from mjcfbuild.check.warp_variant import behaviour, measure

    rows = []
    for robot in plan:
        figures: dict = {}
        for _ in range(rounds):
            for label, path in robot["scenes"]:
                result = measure(path, worlds, steps, device=device)
                best = figures.get(label)
                if best is None or result.steps_per_second > best.steps_per_second:
                    figures[label] = result
        lines = []
        for built_for, path in robot["variants"]:
            line, failure = behaviour(path, hold, device)
            lines.append(f"({built_for}) {line}" + (f" (FAILS: {failure})" if failure else ""))
        solvers = {label: solver_label(path) for label, path in robot["scenes"]}
        rows.append((robot["robot"], figures, solvers, "; ".join(lines)))
        print(f"measured {robot['robot']}", file=sys.stderr)
    return rows


def device_name(device: str) -> str:
    """The device in words: the GPU's name, or the CPU's model and core count."""
    import warp as wp

    found = wp.get_device(device)
    if found.is_cuda:
        return f"{device} ({found.name})"
    model = ""
    with open("/proc/cpuinfo") as info:
        for line in info:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    return f"{device} ({model or 'CPU'}, {os.cpu_count()} cores)"


def table(rows, worlds: int, steps: int, device: str) -> str:
    """The benchmark's table and behaviour lines, as Markdown."""
    lines = [
        f"MuJoCo Warp on {device_name(device)}: {worlds} worlds, {steps} steps, noise on ctrl",
        "",
        "| robot | model | solver | collision geoms | contact pairs | finite | steps/s | vs full |",
        "|---|---|---|---:|---:|---|---:|---:|",
    ]
    for name, figures, solvers, _ in rows:
        base = figures["full model"].steps_per_second
        for label, result in figures.items():
            ratio = result.steps_per_second / base if base else 0.0
            lines.append(
                f"| {name} | {label} | {solvers[label]} | {result.collision_geoms} "
                f"| {result.contact_pairs} "
                f"| {'yes' if result.finite else 'NO'} | {result.steps_per_second:.0f} "
                f"| {ratio:.2f}x |"
            )
    lines.append("")
    lines += [f"- {name} variants in Warp: {line}" for name, _, _, line in rows]
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="go1,g1,panda")
    parser.add_argument("--worlds", type=int, help="default 512 (or the exported folder's)")
    parser.add_argument("--steps", type=int, help="default 50 (or the exported folder's)")
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--rounds", type=int, help="best of this many runs each (default 3)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--export", metavar="DIR", help="write the scenes to measure to DIR")
    where.add_argument("--from", dest="source", metavar="DIR", help="measure an exported DIR")
    args = parser.parse_args()
    given = {"worlds": args.worlds, "steps": args.steps, "rounds": args.rounds}
    settings = {"worlds": 512, "steps": 50, "rounds": 3}
    with tempfile.TemporaryDirectory() as scratch:
        if args.source:
            exported, plan = unpacked(Path(args.source), Path(scratch))
            hold = exported.pop("hold_tolerance", HOLD_TOLERANCE)
            settings.update(exported)
        else:
            os.environ.setdefault("MJCFBUILD_CACHE_DIR", str(Path(scratch) / "cache"))
            plan = planned(args.robots.split(","), Path(scratch))
            hold = HOLD_TOLERANCE
        settings.update({key: value for key, value in given.items() if value is not None})
        if args.export:
            archive = export(plan, Path(args.export), settings)
            size = archive.stat().st_size
            print(f"wrote {args.export}: {PLAN} and {archive.name} ({size} bytes)")
            return
        rows = measured(
            plan, settings["worlds"], settings["steps"], settings["rounds"], args.device, hold
        )
        print(table(rows, settings["worlds"], settings["steps"], args.device))


if __name__ == "__main__":
    main()
