"""mjcfbuild's builds as tasks of your own ``dodo.py``.

One doit task per manifest runs the same build as ``mjcfbuild build``, with the same state: a
model built by either is up to date for the other. doit asks the build's no-op stamp (and,
where a build left none, the build's own task statuses) whether anything changed; when
something did, the build runs its own task graph in the output folder's state, so only what
changed runs, outputs are checked by content (a hand-edited model is rebuilt), the output
folder is locked while it runs and products the plan no longer uses are removed. doit's own
database holds nothing a build needs; :meth:`RobotTasks.doit_config` keeps it in the first
output folder's state folder, not beside ``dodo.py``::

    from mjcfbuild.engine.dodo import RobotTasks

    robots = RobotTasks(["robots/arm/robot.yaml", "robots/dog/robot.yaml"])
    DOIT_CONFIG = {"default_tasks": ["robots"], **robots.doit_config()}

    def task_robots():
        yield from robots.tasks()

Each task is named after its robot (``robots:example_arm``) and every line a build prints
starts with the robot's name.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator
from dataclasses import replace
from pathlib import Path
from typing import Any

from mjcfbuild.engine.context import BuildContext

DATABASE = "dodo/doit.sqlite3"  # in the state folder; the no-op stamp ignores it


class RobotTasks:
    """doit tasks building several manifests, one task each."""

    def __init__(self, manifests: Iterable[str | Path], jobs: int | None = None) -> None:
        kwargs: dict[str, Any] = {"jobs": jobs} if jobs else {}
        self.contexts = [
            replace(BuildContext.from_manifest_file(m, **kwargs), noop_stamp=True)
            for m in manifests
        ]

    def doit_config(self) -> dict[str, str]:
        """``dep_file`` and ``backend`` for ``DOIT_CONFIG``: doit's database in the first
        manifest's state folder (created now: doit opens it before it loads tasks)."""
        if not self.contexts:
            return {}
        database = self.contexts[0].state(DATABASE)
        database.parent.mkdir(parents=True, exist_ok=True)
        return {"dep_file": str(database), "backend": "sqlite3"}

    def tasks(self) -> Iterator[dict]:
        """One task per manifest, named after its robot."""
        names = [ctx.manifest.name for ctx in self.contexts]
        for ctx, name in zip(self.contexts, names, strict=True):
            label = _shown(ctx.manifest_file or ctx.base_dir)
            if names.count(name) > 1:  # two manifests build robots of one name
                name = f"{name}@{_shown(ctx.base_dir)}"
            yield {
                "name": name,
                "doc": f"build {ctx.robot_path.name} from {label}",
                "title": lambda task, label=label: f"{task.name} ({label})",
                "actions": [(build, [ctx])],
                "uptodate": [(up_to_date, [ctx])],
                "verbosity": 2,
            }


def up_to_date(ctx: BuildContext) -> bool:
    """Whether a build of ``ctx`` would run nothing: the no-op stamp says so, or, where the
    last build left no stamp (it failed, or ran another way), every task of its graph is up
    to date."""
    from mjcfbuild.engine import stamp
    from mjcfbuild.engine.status import build_statuses

    assert ctx.manifest_file is not None
    if stamp.nothing_to_do(ctx.manifest_file, ctx.run_check, ctx.allow_outside) is not None:
        return True
    statuses, complete = build_statuses(ctx)
    return complete and all(status.up_to_date for status in statuses)


def build(ctx: BuildContext) -> bool:
    """Build ``ctx`` as ``mjcfbuild build`` does, each line naming the robot; False when it
    failed (doit then reports the task failed)."""
    from mjcfbuild.console import report_error, report_warnings
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import run_build
    from mjcfbuild.errors import MjcfbuildError

    robot = ctx.manifest.name
    try:
        result = run_build(ctx, Progress(stream=sys.stdout, live=False, prefix=f"{robot}: "))
    except MjcfbuildError as error:
        report_error(error, debug=False, base_dir=ctx.base_dir)
        return False
    report_warnings(result.warnings, prefix=f"{robot}: ")
    for failure in result.errors:
        report_error(failure, debug=False, base_dir=ctx.base_dir)
    print(result.summary())
    return not result.errors


def _shown(path: Path) -> str:
    """``path`` relative to the current folder when inside it, else absolute."""
    import os

    relative = os.path.relpath(path)
    return str(path) if relative.startswith("..") else relative
