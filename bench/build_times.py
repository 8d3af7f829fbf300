"""Build times of mjcfbuild: cold, no-op, and after one mesh changed, printed as a table.

    python bench/build_times.py [--robots panda,g1,go1] [--repeat 5]

Each robot is copied into a temporary folder (so a mesh can be edited) and built with the
``mjcfbuild`` command line, timed from the outside as a user would see it. Cold builds find
no worker waiting; the others use the workers the last build left (resident workers, in a
private folder of the benchmark, stopped at its end). The reference converter's times are
the figures measured for the field guide (it rebuilds everything on every run, so its no-op
time is its cold time).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench import robot_data

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "arm"
# Reference converter, cold build with default settings (GUIDE section 1).
REFERENCE_COLD = {"example arm": None, "panda": 4.0, "go1": 14.0, "g1": None}


def compile_package() -> None:
    """Write mjcfbuild's bytecode, as installing it from a wheel does (pip compiles at install
    time). An editable install under PYTHONDONTWRITEBYTECODE=1, as on the machine these
    figures come from, never writes it, and every build process then compiles the package
    from source: 0.05-0.1 s a build, a cost of that setup and not of mjcfbuild."""
    import compileall

    compileall.compile_dir(Path(__file__).resolve().parents[1] / "mjcfbuild", quiet=1)


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


@contextlib.contextmanager
def resident_folder() -> Iterator[Path]:
    """A private folder for the resident workers of one robot's builds (short: a socket's
    path is limited), whose workers are stopped at the end."""
    folder = Path(tempfile.mkdtemp(prefix="mjcfbuild-bench-", dir="/tmp"))
    try:
        yield folder
    finally:
        stop_workers(folder)
        shutil.rmtree(folder, ignore_errors=True)


def stop_workers(folder: Path) -> None:
    """Stop the resident workers waiting in ``folder``."""
    from mjcfbuild.engine.resident import resident_pids, stop

    for pid in resident_pids(folder):
        stop(pid)
    for socket_file in folder.glob("*.sock"):
        socket_file.unlink()


def measure(label: str, manifest: Path, mesh: Path, meshes: int, repeat: int) -> dict:
    """Cold (-j 1 and -j 2), no-op and one-mesh-changed times, then the same with every
    collision mesh decomposed by CoACD, and a second output folder sharing the cache. Cold
    builds find no worker waiting; the others use the workers the last build left."""
    from mjcfbuild.engine.resident import DIR_VARIABLE, VARIABLE

    env = dict(os.environ)
    env.pop("CI", None)  # resident workers on, as on a user's machine
    env[VARIABLE] = "900"
    row = {"robot": label, "meshes": meshes, "reference": REFERENCE_COLD.get(label)}
    output = manifest.parent / "mjcf"
    with tempfile.TemporaryDirectory() as cache, resident_folder() as residents:
        env["MJCFBUILD_CACHE_DIR"] = cache  # cold builds must not reuse cached meshes
        env[DIR_VARIABLE] = str(residents)
        for jobs in (1, 2):
            shutil.rmtree(output, ignore_errors=True)
            shutil.rmtree(Path(cache), ignore_errors=True)
            stop_workers(residents)
            row[f"cold_j{jobs}"] = run_build(manifest, jobs, env)
        time.sleep(2.1)  # let the hash cache trust the fresh files' timestamps
        run_build(manifest, 2, env)
        row["noop"] = statistics.median(run_build(manifest, 2, env) for _ in range(repeat))
        time.sleep(1.0)  # as an edit takes: the waiting workers have tidied up
        nudge_mesh(mesh)
        row["changed"] = run_build(manifest, 2, env)

    decomposing = variant(manifest, "decompose.yaml", "mjcf-decompose")
    with tempfile.TemporaryDirectory() as cache, resident_folder() as residents:
        env["MJCFBUILD_CACHE_DIR"] = cache
        env[DIR_VARIABLE] = str(residents)
        row["decompose_cold"] = run_build(decomposing, 2, env)
        time.sleep(1.0)
        nudge_mesh(mesh)
        row["decompose_changed"] = run_build(decomposing, 2, env)
        second = variant(manifest, "decompose-second.yaml", "mjcf-decompose-second")
        row["decompose_shared"] = run_build(second, 2, env)
    return row


def variant(manifest: Path, name: str, output: str) -> Path:
    """A copy of ``manifest`` decomposing every collision mesh into its own output folder."""
    data = yaml.safe_load(manifest.read_text())
    data["collision"] = {"default": "decompose"}
    data.setdefault("output", {})["folder"] = output
    path = manifest.with_name(name)
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def print_table(rows: list[dict]) -> None:
    """The results as Markdown tables."""
    print("\nmjcfbuild build times, wall clock in seconds (-j 2 unless marked)\n")
    print(
        "| robot | mesh files | cold -j 1 | cold -j 2 | no-op | one mesh changed "
        "| reference converter (every run) |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        reference = f"~{row['reference']:.0f}" if row["reference"] else "n/a"
        print(
            f"| {row['robot']} | {row['meshes']} | {row['cold_j1']:.2f} | {row['cold_j2']:.2f} "
            f"| {row['noop']:.3f} | {row['changed']:.2f} | {reference} |"
        )
    print("\nWith `collision: {default: decompose}` (CoACD on every collision mesh)\n")
    print("| robot | cold | one mesh changed | second output folder, shared cache |")
    print("|---|---:|---:|---:|")
    for row in rows:
        print(
            f"| {row['robot']} | {row['decompose_cold']:.2f} | {row['decompose_changed']:.2f} "
            f"| {row['decompose_shared']:.2f} |"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="panda,g1,go1", help="example-robot-data robots")
    parser.add_argument("--repeat", type=int, default=5, help="no-op runs (median)")
    args = parser.parse_args()
    compile_package()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        manifest, mesh, count = case_example(scratch / "example")
        rows.append(measure("example arm", manifest, mesh, count, args.repeat))
        for name in [n for n in args.robots.split(",") if n]:
            manifest, mesh, count = case_robot(name, scratch / name)
            rows.append(measure(name, manifest, mesh, count, args.repeat))
            print(f"measured {name}", file=sys.stderr)
    print_table(rows)


if __name__ == "__main__":
    main()
