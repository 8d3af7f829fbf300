"""Do two source trees of mjcfbuild build the same bytes? Build both, compare every output file.

    python bench/same_outputs.py BEFORE AFTER [--robots panda,go1,...] [--keep DIR]

BEFORE and AFTER are checkouts of this repository (``git worktree add ../before <commit>``).
Each tree builds, with its own code and a fresh product cache of its own, copies of its
``examples/`` (and of the example quadruped with every optional output and a motor) and the
named robots of example-robot-data and the other description wheels (bench/robot_data.py,
bench/other_wheels.py). Every file a user sees is compared byte for byte:
everything in the copied folders but the build's state folder (``.mjcfbuild/``), whose
``check.json`` is compared as well. Prints one line per differing or missing file and a summary;
exit 1 when anything differs. ``--keep DIR --reuse`` builds only AFTER, against the BEFORE
side an earlier run kept in DIR. This is how a refactor shows it changed no output.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

DEFAULT_ROBOTS = "panda,go1,g1,talos,solo12,ur5,tiago,allegro,upkie,stretch,gr1t1,iiwa7"
STATE = ".mjcfbuild"
COMPARED_STATE = ("check.json",)


def build_all(tree: Path, into: Path, robots: list[str]) -> None:
    """Build the examples and ``robots`` with the mjcfbuild of ``tree`` into ``into``."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(tree)
    env["MJCFBUILD_CACHE_DIR"] = str(into / "cache")
    env["PYTHONHASHSEED"] = "0"
    shutil.copytree(tree / "examples", into / "examples")
    _every_output(into / "examples")
    for manifest in sorted((into / "examples").glob("*/robot.yaml")):
        _build(manifest, env)
    if robots:
        bench = Path(__file__).resolve().parent
        script = (
            "import sys; sys.path.insert(0, sys.argv[1]);"
            "from bench import robot_data, other_wheels;"
            "from pathlib import Path;"
            "name, folder = sys.argv[2], Path(sys.argv[3]);"
            "w = other_wheels.ROBOTS.get(name);"
            "r = robot_data.ALL_ROBOTS.get(name);"
            "print(other_wheels.manifest(w, folder, other_wheels.unpack(w)) if w else "
            "robot_data.manifest(r, folder, robot_data.unpack(r), robot_data.package_root()))"
        )
        for name in robots:
            manifest = subprocess.run(
                [sys.executable, "-c", script, str(bench.parent), name, str(into / name)],
                env=env,
                cwd=into,
                check=True,
                capture_output=True,
                text=True,
            ).stdout.strip()
            _build(Path(manifest), env)


EVERY_OUTPUT = """
  package: true
  page: true
  urdf: exported.urdf
  training: true
actuators:
  rules:
    - joints: ["*knee*"]
      motor: go1_knee
"""


def _every_output(examples: Path) -> None:
    """A copy of the quadruped with every optional output and a motor: those paths compared too."""
    copy = examples / "quadruped_every_output"
    shutil.copytree(examples / "quadruped", copy)
    manifest = copy / "robot.yaml"
    manifest.write_text(manifest.read_text() + EVERY_OUTPUT)


def _build(manifest: Path, env: dict[str, str]) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", "build", str(manifest), "-q", "-j", "2"],
        env=env,
        cwd=manifest.parent,  # never a source tree: `python -m` puts the working folder first
        capture_output=True,
        text=True,
    )
    print(f"  {manifest.parent.name}: exit {done.returncode}", file=sys.stderr)


def compared_files(root: Path) -> set[Path]:
    """The files under ``root`` a user sees (relative paths), the cache left out."""
    found = set()
    for path in root.rglob("*"):
        relative = path.relative_to(root)
        if relative.parts[0] == "cache" or not path.is_file() or path.is_symlink():
            continue
        if STATE in relative.parts and relative.name not in COMPARED_STATE:
            continue
        found.add(relative)
    return found


def compare(before: Path, after: Path) -> list[str]:
    """One line per file that differs or exists on one side only."""
    left, right = compared_files(before), compared_files(after)
    lines = [f"only before: {p}" for p in sorted(left - right)]
    lines += [f"only after: {p}" for p in sorted(right - left)]
    lines += [
        f"differs: {p}"
        for p in sorted(left & right)
        if not filecmp.cmp(before / p, after / p, shallow=False)
    ]
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path, help="the tree before the change")
    parser.add_argument("after", type=Path, help="the tree after the change")
    parser.add_argument(
        "--robots",
        default=DEFAULT_ROBOTS,
        help=f"comma-separated robot names, '' for the examples alone (default: {DEFAULT_ROBOTS})",
    )
    parser.add_argument("--keep", type=Path, help="build here and keep the outputs")
    parser.add_argument(
        "--reuse",
        action="store_true",
        help="with --keep: use the BEFORE side's outputs kept there by an earlier run",
    )
    args = parser.parse_args()
    robots = [name for name in args.robots.split(",") if name]
    with tempfile.TemporaryDirectory() as scratch:
        root = args.keep or Path(scratch)
        for side, tree in (("before", args.before), ("after", args.after)):
            if side == "before" and args.reuse and args.keep and (root / side).is_dir():
                continue
            print(f"building with {tree}", file=sys.stderr)
            build_all(tree.resolve(), root / side, robots)
        differences = compare(root / "before", root / "after")
        count = len(compared_files(root / "before"))
    for line in differences:
        print(line)
    print(f"{count} files compared, {len(differences)} differ")
    sys.exit(1 if differences else 0)


if __name__ == "__main__":
    main()
