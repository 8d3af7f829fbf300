"""Which tasks of a build would run, and why, without running anything.

This is doit's own up-to-date test (the one ``doit info`` uses), read against the build's
database and put in words: which input changed, which parameter, which output was edited or
deleted. ``mjcfbuild check --up-to-date`` and ``mjcfbuild explain`` are built on it.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.graph.uptodate import ParamsUnchanged


@dataclass
class TaskStatus:
    """Whether one task is up to date, and the reasons if it is not."""

    name: str
    title: str
    up_to_date: bool
    reasons: list[str] = field(default_factory=list)
    # Titles of the up-to-date tasks that read what this one writes, directly or further on:
    # they run after it where its outputs come out changed (doit compares them then).
    then: list[str] = field(default_factory=list)


def task_statuses(ctx: BuildContext, tasks: list[dict]) -> list[TaskStatus]:
    """The status of every task in ``tasks`` against the database of ``ctx``'s output folder."""
    from doit.dependency import Dependency, SqliteDB
    from doit.task import dict_to_task

    from mjcfbuild.engine.checker import checker_class
    from mjcfbuild.engine.loader import DATABASE

    objects = [dict_to_task(dict(task)) for task in tasks]
    database = ctx.state(DATABASE)
    if not database.exists():  # never built here; opening the database would create it
        return [
            TaskStatus(task.name, task.title(), False, ["it has not run in this output folder yet"])
            for task in objects
        ]
    by_name = {task.name: task for task in objects}
    manager = Dependency(SqliteDB, str(database), checker_cls=checker_class(ctx.session.hashes))
    try:
        result = []
        for task in objects:
            status = manager.get_status(task, by_name, get_log=True)
            values = manager.get_values(task.name)
            reasons = _reasons(status, task, values, ctx)
            result.append(
                TaskStatus(task.name, task.title(), status.status == "up-to-date", reasons)
            )
        _downstream(objects, result)
        return result
    finally:
        manager.close()


def _downstream(objects: list[Any], statuses: list[TaskStatus]) -> None:
    """Fill each stale task's ``then``: the up-to-date tasks reading its outputs, transitively."""
    # Only files: a task_dep orders tasks but makes none rerun (engine.runner).
    writer = {str(target): task.name for task in objects for target in task.targets}
    readers: dict[str, set[str]] = {}
    for task in objects:
        for path in task.file_dep:
            if str(path) in writer and writer[str(path)] != task.name:
                readers.setdefault(writer[str(path)], set()).add(task.name)
    for status in statuses:
        if status.up_to_date:
            continue
        found, todo = set(), [status.name]
        while todo:
            for reader in readers.get(todo.pop(), ()):
                if reader not in found:
                    found.add(reader)
                    todo.append(reader)
        status.then = [
            other.title for other in statuses if other.name in found and other.up_to_date
        ]


def _never_run(task: Any, ctx: BuildContext) -> str:
    """Why a task with no record of a run is stale: its last run stopped at an output the
    user edited (which it will not write over), or it has not run here."""
    from mjcfbuild.ownership import recorded_foreign

    edited = recorded_foreign(ctx.out_dir).edited
    for target in task.targets:
        if os.path.relpath(target, ctx.out_dir).replace(os.sep, "/") in edited:
            return (
                f"it stops at {ctx.label(target)}, edited by hand since it was built (carry "
                "the edit into robot.yaml, or commit it)"
            )
    # The folder has a database (task_statuses): a task new to the build, or one a failed
    # build did not finish (doit keeps no record of a run that failed).
    return "no finished run of it is recorded here (a new task, or a build stopped before it)"


def _reasons(status: Any, task: Any, values: dict, ctx: BuildContext) -> list[str]:
    if status.status == "up-to-date":
        return []
    if not values:
        return [_never_run(task, ctx)]
    reasons = []
    log = status.reasons
    for path in log.get("changed_file_dep", []):
        reasons.append(f"input changed: {ctx.label(path)}")
    for path in log.get("added_file_dep", []):
        reasons.append(f"new input: {ctx.label(path)}")
    for path in log.get("removed_file_dep", []):
        reasons.append(f"input no longer used: {ctx.label(path)}")
    for path in log.get("missing_target", []):
        reasons.append(f"output missing: {ctx.label(path)}")
    for check, _, _ in log.get("uptodate_false", []):
        if isinstance(check, ParamsUnchanged):
            changed = check.changes(values)
            reasons.append("parameters changed: " + ", ".join(changed[:8]))
        elif getattr(check, "reason", None):
            reasons.append(_relabel(check.reason, ctx))
        else:
            reasons.append("asked to run every time")
    if status.error_reason and not reasons:
        reasons.append(status.error_reason)
    return reasons or ["doit reports it out of date"]


def _relabel(reason: str, ctx: BuildContext) -> str:
    """Show an absolute path at the end of a reason relative to the manifest's folder."""
    head, sep, path = reason.rpartition(": ")
    return f"{head}{sep}{ctx.label(path)}" if sep and path.startswith("/") else reason


def build_statuses(ctx: BuildContext) -> tuple[list[TaskStatus], bool]:
    """Statuses of every task of a build, and whether that is every task.

    When the planning tasks are stale (or never ran), the later tasks depend on a plan that
    does not exist yet, so only the planning tasks are reported (and ``False``).
    """
    from mjcfbuild.engine.tasks import build_tasks, planning_tasks
    from mjcfbuild.outputs import PLAN

    planning = task_statuses(ctx, planning_tasks(ctx))
    if not ctx.state(PLAN).exists() or not all(s.up_to_date for s in planning):
        return planning, False
    return task_statuses(ctx, build_tasks(ctx)), True
