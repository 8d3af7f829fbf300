"""A task family: one kind of build task, declared once, in a module of its own.

A :class:`Family` says everything the engine needs of one kind of task: the step it runs, the
payload the step is given, the format number and tools that make its output what it is, where
it runs, and the doit tasks it adds to the graph. :mod:`mjcfbuild.families.registry` lists
them; the engine derives its tables (versions, workers' preloads, freshness, what compiles the
model) from that list. :func:`file_task` is the one way a family makes a doit task.

Light on purpose: a cluster worker imports the registry for the versions it computes products
under (mjcfbuild.sharing.compute), so nothing here imports doit, MuJoCo or numpy at module
level.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import unreadable_file
from mjcfbuild.graph.uptodate import ParamsUnchanged, always_stale, outputs_intact
from mjcfbuild.sources.packages import ENV_VARIABLES
from mjcfbuild.steps.depfile import Depfile
from mjcfbuild.steps.payloads import Payload
from mjcfbuild.steps.versions import StepFormat

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


@dataclass(frozen=True)
class Family:
    """One kind of build task.

    ``tasks`` makes the family's doit tasks from the graph being built (none where the
    manifest does not ask for them); the registry's order is the order tasks are listed in,
    which is the order doit starts ready ones. ``verify`` (optional) refuses settings before
    any task of the build is made; ``report`` (optional) is its part of report.json.
    """

    name: str  # the task's step name: its versions' key and its format's label
    step: str  # "module:function", imported where the task runs (a worker imports it by name)
    payload: type[Payload]
    format: int  # bump when the step's output for the same inputs changes
    tools: tuple[str, ...]  # distributions whose versions make its output what it is
    tasks: Callable[[Graph], list[dict]]
    stage: Literal["planning", "build"] = "build"
    # Compiles the built model with MuJoCo: runs in the worker that last compiled it, or where
    # its meshes were warmed while it was assembled (engine.session).
    compiles_model: bool = False
    # Writes only to the report (check, previews, tuning): workers of a build that checks
    # preload its module with the check's, and freshness does not count its tasks.
    report_only: bool = False
    verify: Callable[[Graph], None] | None = None
    # What it adds to report.json, read from what its tasks recorded (never from what ran this
    # time, so an up-to-date build reports the same bytes); objects given under one key by
    # two families are merged.
    report: Callable[[GraphContext], dict[str, Any]] | None = None

    @property
    def module(self) -> str:
        """The module of the family's step."""
        return self.step.partition(":")[0]

    def versions(self) -> dict[str, str]:
        """What the step's output depends on besides its inputs: tool versions and its format
        (in a task's up-to-date parameters and in product cache keys)."""
        return StepFormat(self.name, self.format, self.tools).versions()


def file_task(
    ctx: GraphContext,
    family: Family,
    name: str,
    title: str,
    payload: Payload,
    *,
    in_worker: bool,
    file_dep: list[Path],
    targets: list[Path],
    extra_uptodate: list | None = None,
    after: list[str] | None = None,
    absent: list[Path] | None = None,
) -> dict:
    """A doit task running ``family``'s step on ``payload``; up to date while its file
    dependencies, the payload's counted fields and the step's tool versions are unchanged.
    ``absent``: the files the task's planning looked for and did not find (a license file),
    whose appearing changes the task: the graph sees it when it plans the task again, the
    no-op stamp and ``watch`` through the task's ``meta``."""
    assert isinstance(payload, family.payload), f"{family.name} is given {family.payload}"
    params = {
        **payload.uptodate_params(),
        "versions": family.versions(),
        # Where it writes: a renamed model's task must not pass for the run that wrote the
        # old name (doit checks only that targets exist; a kept file of the name would do).
        "targets": [os.path.relpath(p, ctx.base_dir) for p in targets],
    }
    return {
        "task_dep": after or [],
        "name": name,
        "title": lambda _task, title=title: title,
        "doc": title,
        "actions": [(run_step, [ctx, name, family.step, payload.to_dict(), in_worker])],
        "file_dep": sorted({str(p) for p in file_dep}),
        "targets": [str(p) for p in targets],
        "uptodate": [
            ParamsUnchanged(params),
            outputs_intact(ctx.session.hashes, ctx.out_dir),
            *(extra_uptodate or []),
        ],
        "verbosity": 0,
        "clean": True,
        "meta": {"absent": sorted({str(p) for p in absent or ()})},
    }


def task_payload(task: dict) -> dict | None:
    """The payload (as a dict) of a task :func:`file_task` made; None for any other task."""
    for action in task.get("actions", []):
        if isinstance(action, tuple) and action[0] is run_step:
            return action[1][3]
    return None


def run_step(
    ctx: GraphContext,
    name: str,
    step: str,
    payload: dict,
    in_worker: bool,
    task: Any,  # doit's Task, which doit passes to an action that names a `task` parameter
) -> Any:
    """The action of every task: run the step, keep its warnings, report its outputs; a
    failure is doit's ``TaskFailed`` with the error's one line.

    Files the step reports as ``discovered`` (what a xacro expansion included) join the
    task's dependencies before doit records its success, so they are checked from the next
    build on, like the dependencies a compiler writes into a ``.d`` file.
    """
    started = time.perf_counter()
    try:
        result = ctx.session.run_step(step, payload, task=name, in_worker=in_worker)
    except Exception as exc:
        # doit is loaded when an action runs; importing it here keeps this module light.
        from doit.exceptions import TaskFailed

        error = ctx.session.record_failure(name, exc)
        ctx.session.task_warnings[name] = []  # it reruns, and warns again, next time
        return TaskFailed(error.one_line())
    finally:
        ctx.session.timings[name] = time.perf_counter() - started
    ctx.session.warnings.extend(result.get("warnings", []))
    ctx.session.task_warnings[name] = list(result.get("warnings", []))
    # What clean may remove: the files the step reports, checked (outputs) or not (written).
    ctx.session.written.update(result["outputs"], result.get("written", []))
    notes = ["from cache" if result.get("cached") else "", result.get("note", "")]
    if any(notes):
        ctx.session.notes[name] = "; ".join(n for n in notes if n)
    if result.get("stored"):
        ctx.session.cache_grew = True
    if "discovered" in result:
        # What this run read replaces what the last run's depfile listed: a file no longer
        # read would otherwise stay in the list doit saves, and the build stage would find
        # the list changed and run the task a second time.
        task.file_dep.intersection_update({payload["source"]})
        task.file_dep.update(result["discovered"])
    return {"outputs": result["outputs"]}


def largest_first(names: Iterable[str], source: Callable[[str], str]) -> list[str]:
    """``names`` ordered by the size of each one's ``source`` file, largest first.

    doit starts ready tasks in list order, and a long task started last finishes alone on one
    core while the others wait. A mesh's file size is the only estimate of its work known
    before any mesh is read: it puts go1's 13 MB trunk (2.4 s to convert, the others 0.2 s)
    and g1's torso (its slowest decomposition) among the first.
    """

    def size(name: str) -> int:
        try:
            return Path(source(name)).stat().st_size
        except OSError:
            return 0

    return sorted(names, key=lambda name: (-size(name), name))


def discovered_inputs(ctx: GraphContext, depfile: Path) -> tuple[list[Path], list[Callable]]:
    """What the last run of a task recorded in ``depfile`` that it read (the files that still
    exist) and, when a file it looked for appeared or a variable it read changed, an
    up-to-date check that reruns it."""
    recorded = Depfile.read(depfile)
    if recorded is None:
        return [], []
    files = [Path(f) for f in recorded.files if Path(f).exists()]
    stale = recorded.stale_reason(ctx.environ)
    return files, [always_stale(stale)] if stale else []


def read_record(path: Path) -> dict:
    """A task's JSON record; empty when it is absent or unreadable (the task did not run)."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return {}


def require_file(ctx: GraphContext, path: Path, what: str, key: str) -> None:
    """:class:`InputError` unless ``path``, named by manifest key ``key``, is a readable file."""
    problem = unreadable_file(path)
    if problem:
        from mjcfbuild.manifest.pinpoint import key_line

        line = key_line(ctx.manifest_file, key)
        where = f"at {ctx.manifest_label}:{line}" if line else f"in {ctx.manifest_label}"
        raise InputError(f"{what} {problem}", file=ctx.label(path), hint=f"fix '{key}' {where}")


def package_folders(packages: dict[str, Path]) -> dict[str, str]:
    """ROS package name -> its folder, as a payload carries it."""
    return {name: str(path) for name, path in packages.items()}


def ros_environment(ctx: GraphContext) -> dict[str, str]:
    """The ROS variables package lookup reads, as the build sees them."""
    return {key: ctx.environ.get(key, "") for key in ENV_VARIABLES}


def ros_package_index(ctx: GraphContext) -> str:
    """A digest of what those variables offer package lookup now (``environment_index``): a
    task that looks packages up there reruns when one comes to shadow another. Taken once a
    build (its tasks are planned in one moment)."""
    from mjcfbuild.sources.packages import environment_index

    key = (ctx.started_ns, *ros_environment(ctx).values())
    if key not in _PACKAGE_INDEX:
        _PACKAGE_INDEX.clear()  # one build's at a time: watch's next build looks again
        _PACKAGE_INDEX[key] = environment_index(ctx.environ)
    return _PACKAGE_INDEX[key]


_PACKAGE_INDEX: dict[tuple, str] = {}
