"""Where users wait: cold, no-op (fast and full path), one mesh or one joint attribute changed.

    python bench/edit_times.py [--robots panda,go1,g1] [--repeat 5] [--cold-repeat 3] [--jobs 2]
                               [--no-check] [--reference "COMMAND {urdf} {output}"] [--bare]

Each robot is copied into a temporary folder and built with the ``mjcfbuild`` command line
(check and previews included, unless ``--no-check``), timed from the outside as a user would
see it, with mjcfbuild's bytecode written first, as installing it does
(``compile_package`` in build_times). A cold build starts from a fresh cache folder, no
output folder and no resident worker; it is made ``--cold-repeat`` times and the median
shown; each is followed at once by a no-op, as a script or hook runs one (the "first
no-op"). Every build's time to the model is when its "model ready" line came. The no-op is
then timed twice: as ``mjcfbuild build`` runs it (the stamp fast path) and
with ``MJCFBUILD_FULL_BUILD=1`` (the full doit graph). The joint edit changes the damping of
the first joint of the URDF (or xacro), the mesh edit one vertex of one mesh; each edit is
made ``--repeat`` times, alternating, once with the workers the last build left (resident
workers, as in an edit-and-rebuild loop) and once with new workers
(``MJCFBUILD_RESIDENT_WORKERS=0``, as after they left), and the medians are shown. The
workers live in a private folder of the benchmark and are stopped at its end; each edit is
made a second after the last build, as a person editing takes at least that. The same edits
are then made ``--repeat`` times under ``mjcfbuild watch``, timed from the edit to the
watch's "model ready" line (its polling included). ``--bare`` also
makes each cold build and each edit with new workers without the engine's head starts (no
worker started before the manifest is read, none pre-warmed with its modules): what those
save. The
reference converter rebuilds everything on every run; its figures are the ones recorded on
this machine (issue 14) unless ``--reference`` gives a command to time live, in which
``{urdf}`` is the robot's URDF (a xacro source expanded by the build) and ``{output}`` a
fresh folder, for example ``--reference "ros2 run mujoco_ros2_control
make_mjcf_from_robot_description.py --urdf {urdf} --output {output}"`` where ROS is
installed."""

from __future__ import annotations

import argparse
import math
import os
import re
import shlex
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench.build_times import (
    case_example,
    case_robot,
    compile_package,
    nudge_mesh,
    resident_folder,
    stop_workers,
)
from mjcfbuild.engine.resident import DIR_VARIABLE as RESIDENT_DIR_VARIABLE
from mjcfbuild.engine.resident import VARIABLE as RESIDENT_VARIABLE

# The reference converter's full run, measured on this 2-core machine (panda and go1: issue 14;
# g1: issue 43, which timed it beside a cold build).
REFERENCE_RECORDED = {"panda": 5.4, "go1": 14.6, "g1": 3.5}


MODEL_READY = "mjcfbuild: model ready:"

# `--bare`: the command line with neither of the engine's head starts: no workers started
# before the manifest is read (engine.early) and none started ahead of their first step with
# its modules imported (BuildSession.warm_workers); workers start when a step needs one.
BARE_LAUNCHER = (
    "import sys\n"
    "import mjcfbuild.engine.early as early\n"
    "import mjcfbuild.engine.session as session\n"
    "early.start_workers = lambda *args, **kwargs: None\n"
    "session.BuildSession.warm_workers = lambda self, first_build: None\n"
    "from mjcfbuild.cli import main\n"
    "main(sys.argv[1:])\n"
)


def median(values: Iterable[float | None]) -> float:
    """The median of ``values``; NaN (printed ``nan``) where one is missing, as the time to
    the model is from a tree older than its "model ready" line."""
    listed = list(values)
    present = [value for value in listed if value is not None]
    return statistics.median(present) if present and len(present) == len(listed) else math.nan


def timed_build(
    manifest: Path, jobs: int, env: dict, check: bool = True, bare: bool = False
) -> tuple[float, str, float | None]:
    """Wall-clock seconds of one ``mjcfbuild build`` (``bare``: without early or pre-warmed
    workers), its summary line, and the seconds until it announced the model (None where it
    wrote no model: a no-op)."""
    started = time.perf_counter()
    command = [sys.executable, "-c", BARE_LAUNCHER] if bare else [sys.executable, "-m", "mjcfbuild"]
    process = subprocess.Popen(
        command + ["build", str(manifest), "-j", str(jobs)] + ([] if check else ["--no-check"]),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env,
    )
    assert process.stdout is not None
    lines, model = [], None
    for line in process.stdout:  # as the user sees each line come
        if model is None and line.startswith(MODEL_READY):
            model = time.perf_counter() - started
        lines.append(line.rstrip("\n"))
    process.wait()
    seconds = time.perf_counter() - started
    if process.returncode != 0:
        raise SystemExit(f"build of {manifest} failed:\n" + "\n".join(lines))
    summary = [line for line in lines if line.startswith("mjcfbuild: built")]
    return seconds, (summary[-1] if summary else ""), model


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


def measure(
    label: str,
    manifest: Path,
    mesh: Path,
    repeats: tuple[int, int],
    jobs: int,
    check: bool,
    reference: str,
    bare: bool = False,
) -> dict:
    """The times of one robot (seconds) and which tasks ran after each edit; ``repeats``:
    how often each edit and each cold build is made."""
    from mjcfbuild.engine.context import BuildContext

    repeat, cold_repeat = repeats
    env = dict(os.environ)
    env.pop("CI", None)  # resident workers on, as on a user's machine
    env[RESIDENT_VARIABLE] = "900"
    full = {**env, "MJCFBUILD_FULL_BUILD": "1"}
    new_workers = {**env, RESIDENT_VARIABLE: "0"}
    row: dict = {"robot": label}
    output = BuildContext.from_manifest_file(manifest).out_dir
    with tempfile.TemporaryDirectory() as cache, resident_folder() as residents:
        for each in (env, full, new_workers):
            each["MJCFBUILD_CACHE_DIR"] = cache
            each[RESIDENT_DIR_VARIABLE] = str(residents)
        cold_times, cold_models, first_noops = [], [], []
        for _ in range(cold_repeat):
            shutil.rmtree(output, ignore_errors=True)
            shutil.rmtree(cache)
            os.mkdir(cache)
            stop_workers(residents)  # a first build: no worker waits for it
            seconds, _, model = timed_build(manifest, jobs, env, check)
            cold_times.append(seconds)
            cold_models.append(model)
            # at once, as a script or a hook runs it: the files the build just wrote
            first_noops.append(timed_build(manifest, jobs, env, check)[0])
        if bare:  # the same cold build, no worker started before its first step
            bare_times, bare_models = [], []
            for _ in range(cold_repeat):
                shutil.rmtree(output, ignore_errors=True)
                shutil.rmtree(cache)
                os.mkdir(cache)
                stop_workers(residents)
                seconds, _, model = timed_build(manifest, jobs, new_workers, check, bare=True)
                bare_times.append(seconds)
                bare_models.append(model)
            row["cold_bare"] = median(bare_times)
            row["cold_model_bare"] = median(bare_models)
            timed_build(manifest, jobs, env, check)  # the last build's stamp, as before
        row["cold"] = median(cold_times)
        row["cold_model"] = median(cold_models)
        row["noop_first"] = median(first_noops)
        row["noop"] = median(timed_build(manifest, jobs, env, check)[0] for _ in range(repeat))
        row["noop_full"] = median(
            timed_build(manifest, jobs, full, check)[0] for _ in range(repeat)
        )
        times: dict[str, list[float]] = {}
        for _ in range(repeat):
            variants = [("", env, False), ("_new", new_workers, False)]
            if bare:
                variants.append(("_bare", new_workers, True))
            for workers, environment, launch_bare in variants:
                # A second between builds, as an edit takes: the workers the last build left
                # tidy up before they wait, and would otherwise compete with the next build.
                time.sleep(1.0)
                nudge_mesh(mesh)
                seconds, row["mesh_summary"], model = timed_build(
                    manifest, jobs, environment, check, launch_bare
                )
                times.setdefault("mesh" + workers, []).append(seconds)
                times.setdefault("mesh_model" + workers, []).append(model)
                time.sleep(1.0)
                edit_joint(manifest)
                seconds, row["joint_summary"], model = timed_build(
                    manifest, jobs, environment, check, launch_bare
                )
                times.setdefault("joint" + workers, []).append(seconds)
                times.setdefault("joint_model" + workers, []).append(model)
        row.update({name: median(values) for name, values in times.items()})
        row["mesh_watch"], row["joint_watch"] = watched_edits(
            manifest, mesh, repeat, jobs, env, check
        )
        stop_workers(residents)
    row["reference"] = (
        time_reference(reference, manifest, repeat) if reference else REFERENCE_RECORDED.get(label)
    )
    row["reference_live"] = bool(reference)
    return row


def watched_edits(
    manifest: Path, mesh: Path, repeat: int, jobs: int, env: dict, check: bool
) -> tuple[float, float]:
    """Median seconds from each edit (one mesh, one joint; ``repeat`` times each) to the
    "model ready" line of the build ``mjcfbuild watch`` starts for it, on the workers the
    last build left (the watch's own first build is a no-op)."""
    command = [sys.executable, "-m", "mjcfbuild", "watch", str(manifest), "-j", str(jobs)]
    process = subprocess.Popen(
        command + ([] if check else ["--no-check"]),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env,
        # SIGINT as at a terminal, even where this benchmark runs in the background (`&`):
        # a command started with it ignored keeps ignoring it, and Ctrl-C is how it ends.
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    assert process.stdout is not None

    printed: list[str] = []

    def until(prefix: str) -> float:
        for line in process.stdout:
            printed.append(line)
            if line.startswith(prefix):
                return time.perf_counter()
            if "error:" in line:
                raise SystemExit("mjcfbuild watch failed:\n" + "".join(printed[-40:]))
        raise SystemExit("mjcfbuild watch ended")

    edits = {"mesh": lambda: nudge_mesh(mesh), "joint": lambda: edit_joint(manifest)}
    times: dict[str, list[float]] = {kind: [] for kind in edits}
    try:
        until("mjcfbuild: watching")
        for _ in range(repeat):
            for kind, edit in edits.items():
                time.sleep(1.0)
                started = time.perf_counter()
                edit()
                times[kind].append(until(MODEL_READY) - started)
                until("mjcfbuild: watching")  # the check and previews are done
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=60)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
    return median(times["mesh"]), median(times["joint"])


def time_reference(template: str, manifest: Path, repeat: int) -> float:
    """Median wall-clock seconds of the reference converter's command on this robot."""
    from mjcfbuild.engine.context import BuildContext
    from mjcfbuild.outputs import planned_urdf

    urdf = planned_urdf(BuildContext.from_manifest_file(manifest))  # written by the cold build
    times = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as output:
            command = template.format(urdf=shlex.quote(str(urdf)), output=shlex.quote(output))
            started = time.perf_counter()
            done = subprocess.run(command, shell=True, capture_output=True, text=True)
            times.append(time.perf_counter() - started)
            if done.returncode != 0:
                raise SystemExit(f"the reference command failed:\n{command}\n{done.stderr}")
    return median(times)


def print_table(rows: list[dict], jobs: int, check: bool) -> None:
    """The results as a Markdown table."""
    what = "check and previews on" if check else "--no-check"
    print(f"\nmjcfbuild build times, wall clock in seconds, -j {jobs}, {what}\n")
    how = "live" if any(row["reference_live"] for row in rows) else "recorded"
    print(
        "| robot | cold | no-op | no-op, full graph | one mesh changed | one joint damping "
        "changed | one mesh, new workers | one joint, new workers | reference converter "
        f"(every run, {how}) |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        reference = f"{row['reference']:.1f}" if row["reference"] else "n/a"
        print(
            f"| {row['robot']} | {row['cold']:.2f} | {row['noop']:.3f} | {row['noop_full']:.3f} "
            f"| {row['mesh']:.2f} | {row['joint']:.2f} | {row['mesh_new']:.2f} "
            f"| {row['joint_new']:.2f} | {reference} |"
        )
    print(
        "\nUntil the model is written and announced (its check, previews, tuning report and "
        "page follow), and the first no-op right after a cold build; the ratios are against "
        f"the reference converter's run ({how}):\n"
    )
    print(
        "| robot | to the model, cold | one mesh changed | one joint changed | one mesh, new "
        "workers | one joint, new workers | one mesh, watch | one joint, watch | first no-op "
        "| cold / reference | one mesh / reference | one mesh, watch / reference |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        reference = row["reference"]

        def ratio(seconds: float, reference: float | None = reference) -> str:
            return f"{seconds / reference:.2f}x" if reference else "n/a"

        print(
            f"| {row['robot']} | {row['cold_model']:.2f} | {row['mesh_model']:.2f} "
            f"| {row['joint_model']:.2f} | {row['mesh_model_new']:.2f} "
            f"| {row['joint_model_new']:.2f} | {row['mesh_watch']:.2f} "
            f"| {row['joint_watch']:.2f} | {row['noop_first']:.3f} "
            f"| {ratio(row['cold_model'])} | {ratio(row['mesh_model'])} "
            f"| {ratio(row['mesh_watch'])} |"
        )
    if "cold_bare" in rows[0]:
        print(
            "\nNew workers without the engine's head starts (none started before the manifest "
            "is read, none pre-warmed; `--bare`), against the same with them:\n"
        )
        print(
            "| robot | to the model, cold | same, bare | one mesh, new workers | same, bare "
            "| one joint, new workers | same, bare | cold | cold, bare |"
        )
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
        for row in rows:
            print(
                f"| {row['robot']} | {row['cold_model']:.2f} | {row['cold_model_bare']:.2f} "
                f"| {row['mesh_model_new']:.2f} | {row['mesh_model_bare']:.2f} "
                f"| {row['joint_model_new']:.2f} | {row['joint_model_bare']:.2f} "
                f"| {row['cold']:.2f} | {row['cold_bare']:.2f} |"
            )
    print()
    for row in rows:
        print(f"- {row['robot']}, one mesh changed: {row['mesh_summary']}")
        print(f"- {row['robot']}, one joint damping changed: {row['joint_summary']}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="panda,go1,g1", help="example-robot-data robots")
    parser.add_argument("--repeat", type=int, default=5, help="no-op runs and edits (median)")
    parser.add_argument("--cold-repeat", type=int, default=3, help="cold builds (median)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--no-check", action="store_true", help="build without check and previews")
    parser.add_argument(
        "--reference", default="", help="the reference converter's command: {urdf}, {output}"
    )
    parser.add_argument(
        "--bare",
        action="store_true",
        help="also build with neither early nor pre-warmed workers (what those two save)",
    )
    args = parser.parse_args()
    check = not args.no_check
    compile_package()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        manifest, mesh, _ = case_example(folder / "example")
        repeats = (args.repeat, args.cold_repeat)
        rows.append(
            measure(
                "example arm", manifest, mesh, repeats, args.jobs, check, args.reference, args.bare
            )
        )
        for name in [n for n in args.robots.split(",") if n]:
            manifest, mesh, _ = case_robot(name, folder / name)
            rows.append(
                measure(name, manifest, mesh, repeats, args.jobs, check, args.reference, args.bare)
            )
            print(f"measured {name}", file=sys.stderr)
        shutil.rmtree(folder, ignore_errors=True)
    print_table(rows, args.jobs, check)


if __name__ == "__main__":
    main()
