"""mjcfbuild's build tasks for your own ``dodo.py``.

The command line runs these same task generators. In a ``dodo.py``, planning and building are
two task groups, the second created after the first ran (doit's ``create_after``); each
generator is told the name of the group it yields into, since doit names a group's tasks
``<group>:<task>`` and the tasks refer to one another by those names::

    from doit import create_after
    from mjcfbuild.engine.dodo import RobotTasks

    robots = RobotTasks(["robots/arm/robot.yaml", "robots/dog/robot.yaml"])

    def task_plan():
        yield from robots.planning("plan")

    @create_after(executed="plan")
    def task_robots():
        yield from robots.building("robots")

Task names carry the manifest's folder name (``robots:arm/mesh:base``). As in ``mjcfbuild
build``, outputs are checked by content (a hand-edited model is rebuilt), each output folder is
locked while doit runs (a second build of it waits), and converted meshes and decompositions the
plan no longer uses are removed (the ``<folder>/tidy`` task).
"""

from __future__ import annotations

import atexit
import contextlib
from collections.abc import Iterable, Iterator
from pathlib import Path

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.tasks import PLAN, build_tasks, planning_tasks


class RobotTasks:
    """Task generators for several manifests, sharing nothing but the process."""

    def __init__(self, manifests: Iterable[str | Path], jobs: int | None = None) -> None:
        kwargs = {"jobs": jobs} if jobs else {}
        self.contexts = [BuildContext.from_manifest_file(m, **kwargs) for m in manifests]
        self._locks = contextlib.ExitStack()
        self._locked: set[int] = set()
        atexit.register(self._close)

    def planning(self, group: str) -> Iterator[dict]:
        """The expand and plan tasks of every manifest, for the task group named ``group``."""
        for ctx in self.contexts:
            self._lock(ctx)
            yield from _in_group(planning_tasks(ctx, prefix=self._prefix(ctx)), group)

    def building(self, group: str) -> Iterator[dict]:
        """Mesh, assembly, scene, check and tidy tasks of every manifest (after planning ran),
        for the task group named ``group``.

        A manifest not planned yet has none (``doit list`` asks before anything ran).
        """
        for ctx in self.contexts:
            if not ctx.state(PLAN).is_file():
                continue
            self._lock(ctx)
            prefix = self._prefix(ctx)
            tasks = build_tasks(ctx, prefix=prefix, with_planning=False)
            yield from _in_group(tasks, group)
            yield _tidy_task(ctx, tasks, group, prefix)

    def _lock(self, ctx: BuildContext) -> None:
        """Hold ``ctx``'s output folder lock until the process ends, as a CLI build does."""
        from mjcfbuild.engine.progress import Progress
        from mjcfbuild.engine.runner import build_lock, prepare_state

        if id(ctx) in self._locked:
            return
        self._locks.enter_context(build_lock(ctx, Progress()))
        self._locked.add(id(ctx))
        prepare_state(ctx)

    def _close(self) -> None:
        for ctx in self.contexts:
            ctx.session.close()
        self._locks.close()

    @staticmethod
    def _prefix(ctx: BuildContext) -> str:
        return f"{ctx.base_dir.name}/"


def _in_group(tasks: list[dict], group: str) -> Iterator[dict]:
    """``tasks`` as subtasks of ``group``: references between them get the group's name."""
    for task in tasks:
        yield {**task, "task_dep": [f"{group}:{name}" for name in task.get("task_dep", [])]}


def _tidy_task(ctx: BuildContext, tasks: list[dict], group: str, prefix: str) -> dict:
    """Removes products no task of this plan uses, after every other task of the manifest."""
    from mjcfbuild.engine.runner import remove_stale_products, stale_products

    return {
        "name": f"{prefix}tidy",
        "doc": f"remove stale products of {ctx.label(ctx.out_dir)}",
        "task_dep": [f"{group}:{task['name']}" for task in tasks],
        "actions": [(remove_stale_products, [ctx, tasks])],
        "uptodate": [lambda: not stale_products(ctx, tasks)],
        "verbosity": 0,
    }
