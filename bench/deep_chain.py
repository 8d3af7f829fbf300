"""Building a long chain: a snake of small box links, each hanging from the one before.

    python bench/deep_chain.py [--links 100,496,497,2000] [--check]

Each chain is written as a URDF (revolute joints, 5 cm box links with inertia), built from a
fresh folder with a private cache, and timed from the outside; the peak is the resident memory
of the largest process of the build. MuJoCo reads at most 496 nested bodies from an MJCF file
(mjcfbuild.mjcf.depth), so longer chains end at ``plan`` with exit 5: their row shows how soon.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

LINK = """  <link name="l{i}">
    <inertial><origin xyz="0.025 0 0"/><mass value="0.05"/>
      <inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0.025 0 0"/><geometry><box size="0.05 0.02 0.02"/></geometry></visual>
    <collision><origin xyz="0.025 0 0"/>
      <geometry><box size="0.05 0.02 0.02"/></geometry></collision>
  </link>
"""
JOINT = """  <joint name="j{i}" type="{kind}"><parent link="l{parent}"/><child link="l{i}"/>
    <origin xyz="0.05 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
"""
# Runs one build and prints its exit code and the peak resident memory of its processes (KiB).
MEASURE = (
    "import json, resource, subprocess, sys\n"
    "done = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
    "peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss\n"
    "print(json.dumps([done.returncode, peak, done.stderr.strip().splitlines()[:1]]))\n"
)


def snake_urdf(links: int, fixed_every: int = 0) -> str:
    """A chain of ``links`` box links joined by revolute joints about z (every
    ``fixed_every``-th joint fixed instead, when given)."""
    parts = ['<?xml version="1.0"?>\n<robot name="snake">\n']
    for i in range(links):
        parts.append(LINK.format(i=i))
        if i:
            fixed = fixed_every and i % fixed_every == 0
            parts.append(JOINT.format(i=i, parent=i - 1, kind="fixed" if fixed else "revolute"))
    parts.append("</robot>\n")
    return "".join(parts)


def build(links: int, check: bool) -> tuple[int, float, int, str]:
    """Exit code, seconds, peak KiB and first error line of building a ``links`` chain."""
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        (root / "snake.urdf").write_text(snake_urdf(links))
        (root / "robot.yaml").write_text("name: snake\nsource:\n  urdf: snake.urdf\n")
        env = dict(os.environ, XDG_CACHE_HOME=str(root / "cache"))
        argv = [sys.executable, "-m", "mjcfbuild", "build", "-q", str(root / "robot.yaml")]
        if not check:
            argv.insert(4, "--no-check")
        started = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-c", MEASURE, *argv], capture_output=True, text=True, env=env
        )
        seconds = time.perf_counter() - started
        code, peak, error = json.loads(done.stdout)
        return code, seconds, peak, (error[0] if error else "")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", default="100,496,497,2000")
    parser.add_argument("--check", action="store_true", help="also run the check step")
    args = parser.parse_args()
    print("| links | exit | seconds | peak MiB | first error |")
    print("|---:|---:|---:|---:|---|")
    for links in (int(n) for n in args.links.split(",")):
        code, seconds, peak, error = build(links, args.check)
        print(f"| {links} | {code} | {seconds:.1f} | {peak / 1024:.0f} | {error[:90]} |")


if __name__ == "__main__":
    main()
