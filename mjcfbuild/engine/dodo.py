"""mjcfbuild's build tasks for your own ``dodo.py``.

The command line runs these same task generators. In a ``dodo.py``, planning and building are
two task groups, the second created after the first ran (doit's ``create_after``)::

    from doit import create_after
    from mjcfbuild.engine.dodo import RobotTasks

    robots = RobotTasks(["robots/arm/robot.yaml", "robots/dog/robot.yaml"])

    def task_plan():
        yield from robots.planning()

    @create_after(executed="plan")
    def task_robots():
        yield from robots.building()

Task names carry the manifest's folder name (``robots:arm/mesh:base``).
"""

from __future__ import annotations

import atexit
from collections.abc import Iterable, Iterator
from pathlib import Path

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.tasks import PLAN, build_tasks, planning_tasks


class RobotTasks:
    """Task generators for several manifests, sharing nothing but the process."""

    def __init__(self, manifests: Iterable[str | Path], jobs: int | None = None) -> None:
        kwargs = {"jobs": jobs} if jobs else {}
        self.contexts = [BuildContext.from_manifest_file(m, **kwargs) for m in manifests]
        for ctx in self.contexts:
            atexit.register(ctx.close)

    def planning(self) -> Iterator[dict]:
        """The expand and plan tasks of every manifest."""
        for ctx in self.contexts:
            ctx.state_dir.mkdir(parents=True, exist_ok=True)
            yield from planning_tasks(ctx, prefix=self._prefix(ctx))

    def building(self) -> Iterator[dict]:
        """Mesh, assembly and scene tasks of every manifest (after planning ran).

        A manifest not planned yet has none (``doit list`` asks before anything ran).
        """
        for ctx in self.contexts:
            if not ctx.state(PLAN).is_file():
                continue
            yield from build_tasks(ctx, prefix=self._prefix(ctx), with_planning=False)

    @staticmethod
    def _prefix(ctx: BuildContext) -> str:
        return f"{ctx.base_dir.name}/"
