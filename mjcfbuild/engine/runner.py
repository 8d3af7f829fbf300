"""Running a build: lock the output folder, plan, build, clean up, summarise."""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.engine import stamp
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.loader import DATABASE, run_doit
from mjcfbuild.engine.progress import BLOCKED, FAILED, RAN, UP_TO_DATE, Progress
from mjcfbuild.engine.report import record_warnings, write_report
from mjcfbuild.engine.tasks import SOURCE_URDF, build_tasks, planned_urdf, planning_tasks
from mjcfbuild.engine.training_files import remove_stale_variant
from mjcfbuild.errors import CheckError, MjcfbuildError, OutputError
from mjcfbuild.fsutil import remove_stale_temp_files, write_if_changed
from mjcfbuild.manifest.pinpoint import pinpoint
from mjcfbuild.sources.origins import point_at_source, point_warning_at_source

if TYPE_CHECKING:
    from mjcfbuild.engine.workers import WorkerPool


@dataclass
class BuildResult:
    """What a build did."""

    robot: Path
    scene: Path
    ran: list[str] = field(default_factory=list)
    up_to_date: list[str] = field(default_factory=list)
    blocked: list[str] = field(default_factory=list)
    errors: list[MjcfbuildError] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    slowest: list[tuple[str, float]] = field(default_factory=list)
    seconds: float = 0.0
    engine_log: str = ""

    @property
    def ok(self) -> bool:
        """Whether every task succeeded."""
        return not self.errors

    def summary(self) -> str:
        """The one line printed at the end of every build."""
        parts = [f"{len(self.ran)} run", f"{len(self.up_to_date)} up to date"]
        if self.errors:
            parts.append(f"{len(self.errors)} failed")
        if self.blocked:
            parts.append(f"{len(self.blocked)} not run")
        if self.warnings:
            parts.append(f"{len(self.warnings)} warning{'s' if len(self.warnings) > 1 else ''}")
        state = "failed" if self.errors else "built"
        return f"mjcfbuild: {state} {self.robot.name}: {', '.join(parts)} in {self.seconds:.2f} s"


@contextlib.contextmanager
def build_lock(ctx: BuildContext, progress: Progress) -> Iterator[None]:
    """Hold the output folder's lock; a second build of it waits instead of interleaving."""
    try:
        ctx.state_dir.mkdir(parents=True, exist_ok=True)
        handle = open(ctx.state("lock"), "w")  # noqa: SIM115 - held for the whole build
    except OSError as exc:
        raise OutputError(
            f"cannot write to the output folder: {exc.strerror}",
            file=ctx.label(ctx.out_dir),
            hint="check its permissions, or set output.folder",
        ) from None
    with handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            if not progress.quiet:
                progress.stream.write(
                    f"mjcfbuild: waiting for another build of {ctx.label(ctx.out_dir)}\n"
                )
                progress.stream.flush()
            fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def run_build(
    ctx: BuildContext, progress: Progress | None = None, workers: WorkerPool | None = None
) -> BuildResult:
    """Build ``ctx``'s manifest; never raises for a failing task (see ``result.errors``).

    ``workers`` (mjcfbuild.engine.early) are used if they suit the build, else stopped.
    """
    from mjcfbuild.engine.resident import answer_seconds, idle_seconds, most_workers

    # A bad value stops the build before it starts, not in a step.
    if idle_seconds(os.environ) > 0:
        answer_seconds(os.environ)
        most_workers(os.environ)
    session = ctx.new_session()  # a context built twice reports each build's own findings
    if workers is not None and not session.adopt(workers):
        workers.close()  # importing and processing meshes for nothing: free the CPU
    progress = progress or Progress()
    progress.notes = session.notes
    started = time.perf_counter()
    result = BuildResult(robot=ctx.robot_path, scene=ctx.scene_path)
    tasks: list[dict] = []
    try:
        _ = ctx.sharing_choice  # a bad remote or executor address stops the build before it starts
        with build_lock(ctx, progress):
            # Everything this build writes in the folder, its hash cache, stamp and report
            # included, is written while it holds the lock: a build that waited for it
            # removes what looks like a killed build's temporary files.
            try:
                tasks = _build_locked(ctx, progress, result)
            finally:
                ctx.session.close()
                progress.clear()
            _summarise(result, progress, ctx, started)
            if ctx.noop_stamp and ctx.stamp_key and tasks and result.ok and not result.warnings:
                stamp.record_build(ctx, tasks, len(result.ran) + len(result.up_to_date))
    finally:
        ctx.session.close()  # for a build stopped before it took the lock; else it did nothing
        progress.clear()
    if not result.seconds:
        _summarise(result, progress, ctx, started)
    return result


def _build_locked(ctx: BuildContext, progress: Progress, result: BuildResult) -> list[dict]:
    """The build itself, under the folder's lock; the tasks of its second stage."""
    tasks: list[dict] = []
    if ctx.stamp_key is not None:  # whichever way it was started
        stamp.discard(ctx.stamp_key, ctx.run_check)
    prepare_state(ctx)
    remove_stale_variant(ctx)
    # Workers start while this process plans, importing until their first step comes.
    ctx.session.warm_workers(first_build=not ctx.state(DATABASE).exists())
    planning = planning_tasks(ctx)
    doit_output = _run_stage(ctx, planning, progress, result)
    if not result.errors:
        tasks = build_tasks(ctx)
        doit_output += _run_stage(ctx, tasks, progress, result)
        if not result.errors:
            remove_stale_products(ctx, tasks)
        # A failed check is what the report is for; any other failure means the model
        # on disk is an earlier one, which the report must not claim to describe.
        model_built = all(isinstance(e, CheckError) for e in result.errors)
        ctx.session.finish_sharing()  # uploads are done (or given up) before the build returns
        if model_built and ctx.robot_path.exists():
            names = list(dict.fromkeys(task["name"] for task in [*planning, *tasks]))
            write_report(ctx, record_warnings(ctx, names))
    if ctx.session.cache_grew:
        _prune_cache(ctx)
    result.engine_log = doit_output if result.errors else ""
    return tasks


def _summarise(result: BuildResult, progress: Progress, ctx: BuildContext, started: float) -> None:
    result.ran = progress.names(RAN)
    result.up_to_date = progress.names(UP_TO_DATE)
    result.blocked = progress.names(BLOCKED)
    warnings = list(dict.fromkeys(ctx.session.warnings))
    for urdf in _expanded_urdfs(ctx):
        label = ctx.label(urdf)
        warnings = [point_warning_at_source(w, urdf, label, ctx.base_dir) for w in warnings]
    result.warnings = warnings
    result.slowest = progress.slowest()
    result.seconds = max(time.perf_counter() - started, 1e-9)


def _run_stage(
    ctx: BuildContext, tasks: list[dict], progress: Progress, result: BuildResult
) -> str:
    code, output = run_doit(ctx, tasks, progress, ["run"])
    failed = progress.names(FAILED)
    for name in failed:
        error = ctx.session.failures.get(name)
        if error is None:
            message = progress.failure_messages.get(name, "failed")
            error = MjcfbuildError(f"{name}: {_first_line(message)}")
            ctx.session.failures[name] = error
        if ctx.manifest_file is not None:
            error = pinpoint(error, ctx.manifest_label, ctx.manifest_file)
        for urdf in _expanded_urdfs(ctx):  # where their elements were written (xacro)
            point_at_source(error, urdf, ctx.label(urdf), ctx.base_dir)
        if error not in result.errors:
            result.errors.append(error)
    if code != 0 and not result.errors:
        message = (
            progress.failure_messages.get("(doit)") or output.strip() or f"doit exited with {code}"
        )
        result.errors.append(MjcfbuildError(f"build engine error: {_first_line(message)}"))
    return output


def _expanded_urdfs(ctx: BuildContext) -> list[Path]:
    """The URDFs a build makes that errors may point at: the expanded source, the parts'
    and the composed one."""
    from mjcfbuild.compose.tasks import part_urdf

    parts = [part_urdf(ctx, index) for index in range(len(ctx.manifest.attach))]
    return [ctx.state(SOURCE_URDF), planned_urdf(ctx), *parts]


def _first_line(text: str) -> str:
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[-1] if lines else text


def prepare_state(ctx: BuildContext) -> None:
    """The state folder ignores itself in git; stdin input is stored; stale temp files go."""
    write_if_changed(
        ctx.state(".gitignore"), b"# mjcfbuild's build state; not for version control\n*\n"
    )
    remove_stale_temp_files(ctx.out_dir)
    remove_stale_temp_files(ctx.state_dir)
    if ctx.manifest.source.description == "-":
        data = sys.stdin.buffer.read()
        write_if_changed(ctx.source_path, data)


def _prune_cache(ctx: BuildContext) -> None:
    """Keep the shared cache under its size cap after a build added to it."""
    from mjcfbuild.engine.store import ProductStore

    settings = ctx.cache_settings()
    ProductStore(Path(settings["folder"]), settings["max_bytes"]).prune()


def stale_products(ctx: BuildContext, tasks: list[dict]) -> list[Path]:
    """Converted meshes and decompositions no task of this build uses."""
    used = {name.split(":", 1)[1] for name in (t["name"] for t in tasks) if ":" in name}
    stale = []
    for folder in (ctx.products_dir, ctx.state_dir / "decompositions"):
        if not folder.is_dir():
            continue
        # <id>/, <id>.json and <id>.deps.json belong to the task of <id>
        stale += [e for e in sorted(folder.iterdir()) if e.name.split(".", 1)[0] not in used]
    return stale


def remove_stale_products(ctx: BuildContext, tasks: list[dict]) -> None:
    """Delete converted meshes and decompositions no task of this build uses."""
    for entry in stale_products(ctx, tasks):
        shutil.rmtree(entry) if entry.is_dir() else entry.unlink()
