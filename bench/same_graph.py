"""Does a refactor of the engine keep every task as it was, and an existing build up to date?

    python bench/same_graph.py BEFORE AFTER [--example arm] [--extra "YAML appended"]

Copies an example of BEFORE (``examples/<name>``, robot.yaml with ``--extra`` appended), builds
it with BEFORE's code, then prints each task whose name, title, file dependencies, targets,
task dependencies, up-to-date parameters, step or payload differ between the two trees' graphs
of that folder (the trees' own paths read as one), and builds it with AFTER's code with the
no-op stamp off: doit must find every task up to date (a task whose dependencies lie inside
the source tree, like the report page's template, is listed with the reason). Exit 1 when
anything differs or reran.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

DUMP = """
import json, sys
from pathlib import Path
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.tasks import build_tasks

ctx = BuildContext.from_manifest_file(Path(sys.argv[1]))
tasks = {}
for task in build_tasks(ctx):
    _, args = task["actions"][0]
    tasks[task["name"]] = {
        "title": task["title"](None),
        "file_dep": task["file_dep"],
        "targets": task["targets"],
        "task_dep": task["task_dep"],
        "params": task["uptodate"][0].params,
        "step": args[2],
        "payload": args[3],
        "in_worker": args[4],
    }
print(json.dumps(tasks, sort_keys=True).replace(sys.argv[2], "<tree>"))
"""


def _run(tree: Path, args: list[str], env: dict[str, str], cwd: Path) -> str:
    # In a folder of neither tree: Python puts the current folder before PYTHONPATH.
    result = subprocess.run(
        [sys.executable, *args],
        cwd=cwd,
        env={**env, "PYTHONPATH": str(tree)},
        capture_output=True,
        text=True,
        check=False,
    )
    if result.returncode != 0:
        sys.exit(f"{tree}: {' '.join(args[:3])} failed:\n{result.stderr[-2000:]}")
    return result.stdout


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    parser.add_argument("--example", default="arm")
    parser.add_argument("--extra", default="", help="YAML appended to robot.yaml (\\n for lines)")
    options = parser.parse_args()
    before, after = options.before.resolve(), options.after.resolve()
    with tempfile.TemporaryDirectory(prefix="same-graph-") as scratch:
        top = Path(scratch)
        ignore = shutil.ignore_patterns("mjcf")
        shutil.copytree(before / "examples", top / "examples", ignore=ignore)
        manifest = top / "examples" / options.example / "robot.yaml"
        manifest.write_text(manifest.read_text() + options.extra.replace("\\n", "\n"))
        env = {**os.environ, "MJCFBUILD_CACHE_DIR": str(top / "cache"), "PYTHONHASHSEED": "0"}
        _run(before, ["-m", "mjcfbuild", "build", str(manifest), "-q"], env, top)
        graphs = [
            json.loads(_run(tree, ["-c", DUMP, str(manifest), str(tree)], env, top))
            for tree in (before, after)
        ]
        differ = sorted(
            name
            for name in set(graphs[0]) | set(graphs[1])
            if graphs[0].get(name) != graphs[1].get(name)
        )
        for name in differ:
            print(f"task differs: {name}")
        env["MJCFBUILD_FULL_BUILD"] = "1"  # the no-op stamp off: doit decides
        explained = _run(after, ["-m", "mjcfbuild", "explain", str(manifest)], env, top)
        reran = [line for line in explained.splitlines() if "up to date" not in line]
        for line in reran:
            print(f"after: {line}")
        print(f"{len(graphs[1])} tasks, {len(differ)} differ; after {options.after}: ", end="")
        print("every task up to date" if not reran else "some would run (above)")
        return 1 if differ or reran else 0


if __name__ == "__main__":
    raise SystemExit(main())
