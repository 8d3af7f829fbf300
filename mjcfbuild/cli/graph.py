"""``mjcfbuild graph``: the task graph of a build, as text or as DOT for Graphviz."""

from __future__ import annotations

import argparse
from pathlib import Path

from mjcfbuild.cli import chosen_manifest, load_context, manifest_argument
from mjcfbuild.errors import EXIT_OK


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "graph",
        help="print the task graph (text, or --dot for Graphviz)",
        description="Print the tasks of a build, what each reads and which tasks it waits for.",
    )
    manifest_argument(parser)
    parser.add_argument("--dot", action="store_true", help="Graphviz DOT, for `dot -Tsvg`")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the graph."""
    from mjcfbuild.engine.tasks import build_tasks, planning_tasks
    from mjcfbuild.outputs import PLAN

    ctx = load_context(chosen_manifest(args), args)
    tasks = build_tasks(ctx) if ctx.state(PLAN).exists() else planning_tasks(ctx)
    producer = {target: task["name"] for task in tasks for target in task["targets"]}
    edges = []
    inputs = []
    for task in tasks:
        for dep in task["file_dep"]:
            if dep in producer:
                edges.append((producer[dep], task["name"]))
            else:
                inputs.append((ctx.label(dep), task["name"]))
        edges += [(before, task["name"]) for before in task.get("task_dep", [])]
    edges = sorted(set(edges))
    print(_dot(tasks, edges, inputs) if args.dot else _text(tasks, edges, inputs))
    if not ctx.state(PLAN).exists():
        print("# the mesh, assembly and check tasks appear once the plan has been made (build)")
    return EXIT_OK


def _text(tasks, edges, inputs) -> str:
    lines = []
    for task in tasks:
        name = task["name"]
        after = [a for a, b in edges if b == name]
        reads = sorted({path for path, b in inputs if b == name})
        lines.append(f"{name}  ({task['doc']})")
        if after:
            lines.append(f"  after: {', '.join(after)}")
        if reads:
            shown = ", ".join(reads[:6]) + (f", ... ({len(reads)} files)" if len(reads) > 6 else "")
            lines.append(f"  reads: {shown}")
    return "\n".join(lines)


def _dot(tasks, edges, inputs) -> str:
    lines = ["digraph mjcfbuild {", "  rankdir=LR;", "  node [shape=box, style=rounded];"]
    for task in tasks:
        lines.append(f'  "{task["name"]}";')
    for path in sorted({p for p, _ in inputs}):
        lines.append(f'  "{path}" [shape=note, label="{Path(path).name}"];')
    for path, task in sorted(set(inputs)):
        lines.append(f'  "{path}" -> "{task}";')
    for before, after in edges:
        lines.append(f'  "{before}" -> "{after}";')
    lines.append("}")
    return "\n".join(lines)
