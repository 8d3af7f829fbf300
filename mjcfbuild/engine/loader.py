"""The doit ``TaskLoader2`` of a build, and running doit on it."""

from __future__ import annotations

import contextlib
import io
from collections.abc import Iterator
from typing import Any

import doit.plugin
from doit.cmd_base import TaskLoader2
from doit.doit_cmd import DoitMain
from doit.task import dict_to_task

from mjcfbuild.engine.checker import checker_class
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.progress import Progress, ProgressReporter

DATABASE = "doit.sqlite3"


class BuildLoader(TaskLoader2):
    """Hands doit a ready list of tasks and the configuration of an mjcfbuild build."""

    def __init__(self, ctx: BuildContext, tasks: list[dict], progress: Progress) -> None:
        super().__init__()
        self.ctx = ctx
        self.tasks = tasks
        self.progress = progress

    def setup(self, opt_values: dict[str, Any]) -> None:
        # doit opens its database before loading tasks: the folder must exist by then.
        self.ctx.state_dir.mkdir(parents=True, exist_ok=True)

    def load_doit_config(self) -> dict:
        jobs = self.ctx.jobs
        return {
            "dep_file": str(self.ctx.state(DATABASE)),
            "backend": "sqlite3",
            "check_file_uptodate": checker_class(self.ctx.session.hashes),
            "reporter": ProgressReporter(self.progress, self.ctx.session.timings),
            "verbosity": 0,
            "continue": True,
            "num_process": jobs if jobs > 1 else 0,
            "par_type": "thread",
        }

    def load_tasks(self, cmd: Any, pos_args: list[str]) -> list:
        # Without capture, doit leaves sys.stdout and sys.stderr alone. With it, each of its
        # threads swaps them for its task and puts back what it found: in any order, and
        # after an interrupted stage has returned, so that the line saying so went nowhere.
        return [dict_to_task({**task, "io": {"capture": False}}) for task in self.tasks]


def run_doit(
    ctx: BuildContext, tasks: list[dict], progress: Progress, command: list[str]
) -> tuple[int, str]:
    """Run a doit command on ``tasks``; its exit code and whatever doit printed."""
    loader = BuildLoader(ctx, tasks, progress)
    output = io.StringIO()
    with (
        contextlib.redirect_stdout(output),
        contextlib.redirect_stderr(output),
        only_doits_own_plugins(),
    ):
        code = DoitMain(loader, config_filenames=()).run(command)
    return code, output.getvalue()


@contextlib.contextmanager
def only_doits_own_plugins() -> Iterator[None]:
    """Run doit without the plugins other installed packages declare: a build uses doit's own
    command, backend and reporter, whatever is installed beside it, and looking them up reads
    the metadata of every installed package on each run (30 ms of a rebuild here)."""
    saved = doit.plugin.entry_points_impl
    doit.plugin.entry_points_impl = lambda: lambda group: ()
    try:
        yield
    finally:
        doit.plugin.entry_points_impl = saved
