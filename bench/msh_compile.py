"""What the products' binary copies save MuJoCo: compiles of a built model from OBJ and MSH.

    python bench/msh_compile.py [--robots g1,go1,panda] [--repeat 5]

Each robot of example-robot-data is built once (``--no-check``) in a temporary folder. Its
published model is then compiled in fresh processes, reading every mesh either from the
published OBJ file or from its product's binary copy (mjcfbuild.meshes.mshfile), as the
build's steps do: the first compile of a process (MuJoCo processes every mesh) and a second
one (from MuJoCo's cache), the median of ``--repeat`` processes each. Both must give the same
model; the benchmark says so or stops.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench.build_times import case_robot

# Run in a fresh process: compile the model twice, reading each asset from ``sources``.
TIMING = r"""
import json, sys, time
from pathlib import Path
import numpy as np
from mjcfbuild.check.loading import asset_sources, spec_reading_sources
import mujoco
model, report, copies = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3] == "msh"
sources = asset_sources(report)
if not copies:  # the products' OBJ files: the copies left out
    from mjcfbuild.check.loading import AssetSource
    sources = {name: AssetSource(source.product) for name, source in sources.items()}
times = []
for _ in range(2):
    spec = spec_reading_sources(model, sources)
    started = time.perf_counter()
    compiled = spec.compile()
    times.append(time.perf_counter() - started)
read = sorted({spec.meshes[i].file.rsplit(".", 1)[-1] for i in range(len(spec.meshes))})
import hashlib
arrays = (compiled.mesh_vert, compiled.mesh_face, compiled.mesh_normal, compiled.body_mass,
          compiled.body_inertia, compiled.geom_size, compiled.geom_pos, compiled.geom_quat)
digest = hashlib.md5(b"".join(np.asarray(a).tobytes() for a in arrays)).hexdigest()
print(json.dumps({"times": times, "read": read, "digest": digest}))
"""


def compile_times(model: Path, report: Path, kind: str) -> dict:
    """One fresh process's two compile times of ``model`` reading ``kind`` files."""
    done = subprocess.run(
        [sys.executable, "-c", TIMING, str(model), str(report), kind],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    """Build each robot, time its compiles both ways, print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="g1,go1,panda")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    rows = []
    for name in args.robots.split(","):
        with tempfile.TemporaryDirectory() as folder:
            manifest, _, meshes = case_robot(name, Path(folder))
            env = {**os.environ, "MJCFBUILD_CACHE_DIR": str(Path(folder) / "cache")}
            env["MJCFBUILD_RESIDENT_WORKERS"] = "0"
            subprocess.run(
                [sys.executable, "-m", "mjcfbuild", "build", str(manifest), "--no-check", "-q"],
                check=True,
                env=env,
            )
            output = manifest.parent / "mjcf"
            model = next(output.glob("*.xml"))
            if model.name == "scene.xml":
                model = next(p for p in output.glob("*.xml") if p.name != "scene.xml")
            report = output / ".mjcfbuild" / "assembly.json"
            runs = {
                kind: [compile_times(model, report, kind) for _ in range(args.repeat)]
                for kind in ("obj", "msh")
            }
            if runs["obj"][0]["digest"] != runs["msh"][0]["digest"]:
                raise SystemExit(f"{name}: the copies compile to another model")
            row = [name, str(meshes)]
            for kind in ("obj", "msh"):
                for which in (0, 1):
                    row.append(f"{statistics.median(r['times'][which] for r in runs[kind]):.3f}")
            row.append("/".join(runs["msh"][0]["read"]))
            rows.append(row)
    print("| robot | meshes | OBJ first | OBJ again | MSH first | MSH again | read |")
    print("|---|---:|---:|---:|---:|---:|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
