"""Running a build: lock the output folder, plan, build, clean up, summarise."""

from __future__ import annotations

import contextlib
import os
import shutil
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild import interrupts
from mjcfbuild.engine import stamp, written
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.earlier_folders import Abandoned, remove_earlier_folders
from mjcfbuild.engine.guard import (
    check_output_folder,
    check_outputs_are_not_inputs,
    claim_output_folder,
)
from mjcfbuild.engine.loader import DATABASE, run_doit
from mjcfbuild.engine.outputs_off import Leftover, remove_leftovers
from mjcfbuild.engine.placing import expanded_urdfs, placed_warnings
from mjcfbuild.engine.progress import BLOCKED, FAILED, RAN, UP_TO_DATE, Progress
from mjcfbuild.engine.tasks import build_tasks, planning_tasks
from mjcfbuild.engine.training_files import remove_renamed_model, remove_stale_variant
from mjcfbuild.errors import CheckError, InputError, MjcfbuildError, OutputError, write_failure
from mjcfbuild.failpoints import failpoint
from mjcfbuild.fsutil import TEMP_SUFFIX, remove_stale_temp_files, write_if_changed
from mjcfbuild.manifest.pinpoint import pinpoint
from mjcfbuild.outputs import PREVIEWS_RECORD, SOURCE_URDF, report_dir
from mjcfbuild.sources.origins import point_at_source

if TYPE_CHECKING:
    from mjcfbuild.engine.folderlock import Holder
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
    """Hold the output folder's lock; a second build of it waits instead of interleaving,
    saying who holds it, and gives up after ``--timeout`` seconds naming the holder.

    The folder is checked first (:mod:`mjcfbuild.engine.guard`): nothing is written, not even
    the lock, in a folder the build may not write."""
    from mjcfbuild.engine.context import DEFAULT_STEP_TIMEOUT
    from mjcfbuild.engine.folderlock import LockBusy, folder_lock

    check_output_folder(ctx)

    folder = ctx.label(ctx.out_dir)
    seconds = DEFAULT_STEP_TIMEOUT if ctx.step_timeout is None else ctx.step_timeout

    def waiting(holder: Holder | None) -> None:
        if not progress.quiet:
            who = f" (held by {holder.describe()})" if holder else ""
            progress.stream.write(f"mjcfbuild: waiting for another build of {folder}{who}\n")
            progress.stream.flush()

    held = contextlib.ExitStack()
    try:  # only taking the lock: an error of the build itself is not about the lock
        ctx.state_dir.mkdir(parents=True, exist_ok=True)
        held.enter_context(folder_lock(ctx.state("lock"), seconds, waiting))
    except LockBusy as busy:
        holder = busy.holder
        who = f"another build ({holder.describe()})" if holder else "another build"
        raise OutputError(
            f"{who} still holds the output folder's lock after {busy.seconds:g} s",
            file=folder,
            hint=f"{_lock_hint(holder)}; --timeout sets how long to wait",
        ) from None
    except OSError as exc:
        raise write_failure(exc) or OutputError(
            f"cannot write to the output folder: {exc.strerror}",
            file=folder,
            hint="check its permissions, or set output.folder",
        ) from None
    with held:
        state = ctx.state_dir.stat()
        ctx.session.state_folder = (state.st_dev, state.st_ino)
        claim_output_folder(ctx)
        yield


def _lock_hint(holder: Holder | None) -> str:
    """What to do about the build that holds a folder's lock."""
    from mjcfbuild.engine.folderlock import STOPPED, UNKNOWN

    if holder is None:
        return "let it finish"
    state = holder.state()
    if state == STOPPED:
        return f"it is stopped: resume it (fg in its shell, or kill -CONT {holder.pid}) or end it"
    if state == UNKNOWN:
        return f"let it finish on {holder.host}, or end it there"
    return f"let it finish, or end it (kill {holder.pid})"


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
                tasks = _build_locked(ctx, progress, result, started)
                ctx.session.close()
            except OSError as exc:  # the folder's own files (state, hash cache, report)
                unwritable = write_failure(exc) or _folder_removed(ctx, exc)
                if unwritable is None:
                    raise
                result.errors.append(unwritable)
                tasks = []
            finally:
                ctx.session.close()
                progress.clear()
            if _state_folder_replaced(ctx):
                # What it wrote before went with the folder, and its steps failed on files
                # that went with it: one error says why.
                result.errors = [_removed(ctx)]
            _summarise(result, progress, ctx, started, tasks)
            failpoint("stamp")
            # No stamp saying the outputs are current if SIGINT came and its
            # KeyboardInterrupt was lost (mjcfbuild.interrupts).
            interrupts.check()
            if ctx.noop_stamp and ctx.stamp_key and tasks and result.ok:
                count = len(result.ran) + len(result.up_to_date)
                stamp.record_build(ctx, tasks, count, _model_warnings(ctx))
    finally:
        ctx.session.close()  # for a build stopped before it took the lock; else it did nothing
        progress.clear()
    if not result.seconds:
        _summarise(result, progress, ctx, started, [])
    interrupts.check()  # nor a result that reads as a success
    return result


def _folder_removed(ctx: BuildContext, exc: OSError) -> OutputError | None:
    """The error of a build whose output folder (or its state folder) was removed while it
    ran (``rm -rf mjcf`` during a build): a file it had written, or was writing, was gone."""
    if not isinstance(exc, FileNotFoundError) or not _state_folder_replaced(ctx):
        return None
    return _removed(ctx)


def _state_folder_replaced(ctx: BuildContext) -> bool:
    """Whether the state folder the build took is gone, or is another folder now (a step
    made it again after the folder was removed)."""
    try:
        state = ctx.state_dir.stat()
    except OSError:
        return True
    return ctx.session.state_folder not in (None, (state.st_dev, state.st_ino))


def _removed(ctx: BuildContext) -> OutputError:
    return OutputError(
        "was removed while the build ran; nothing in it is current",
        file=ctx.label(ctx.out_dir),
        hint="build again",
    )


def _build_locked(
    ctx: BuildContext, progress: Progress, result: BuildResult, started: float
) -> list[dict]:
    """The build itself, under the folder's lock; every task of the build in graph order (the
    planning tasks alone where planning failed). ``started`` (a ``perf_counter``): when the
    build began, for the line announcing the model."""
    tasks: list[dict] = []
    if ctx.stamp_key is not None:  # whichever way it was started
        # Both kinds (with and without the check): the outputs this build writes must not be
        # compared later with an older build's record of them (engine.guard's fallback).
        for run_check in (True, False):
            stamp.discard(ctx.stamp_key, run_check)
    prepare_state(ctx)
    remove_stale_variant(ctx)
    if not ctx.manifest.check.previews:  # the pictures an earlier build drew are not current
        from mjcfbuild.steps.previews import no_pictures  # only where needed

        no_pictures(report_dir(ctx) / "previews", ctx.state(PREVIEWS_RECORD))
    _say_off(ctx, progress, remove_leftovers(ctx))
    # Workers start while this process plans, importing until their first step comes.
    ctx.session.warm_workers(first_build=not ctx.state(DATABASE).exists())
    planning = planning_tasks(ctx)
    try:
        doit_output = _run_stage(ctx, planning, progress, result)
        failpoint("stages")  # between the two stages: the tests interrupt the build here
        if not result.errors:
            tasks = build_tasks(ctx)
            # Only now are the files xacro included known; nothing outside the state
            # folder has been written yet.
            check_outputs_are_not_inputs(ctx, [*planning, *tasks])
            model_tasks = _model_tasks(ctx, tasks)
            _after_the_model(tasks, model_tasks)
            progress.announce_model(model_tasks, _model_line(ctx), started)
            doit_output += _run_stage(ctx, tasks, progress, result)
            if not result.errors:
                remove_stale_products(ctx, tasks)
            # A failed check is what the report is for; any other failure means the model
            # on disk is an earlier one, which the report must not claim to describe.
            model_built = all(isinstance(e, CheckError) for e in result.errors)
            if model_built and ctx.robot_path.exists():
                # once the new name's model is there, not before
                # Names and folders change with a rebuild of the model: what is kept there is
                # said then, not at every build after.
                rebuilt = bool(set(model_tasks) & set(progress.names(RAN)))
                removed, kept = remove_renamed_model(ctx)
                _say_removed(ctx, progress, removed, kept if rebuilt else [])
                if rebuilt:
                    abandoned = remove_earlier_folders(ctx)
                    for folder in abandoned:  # --fail-on-change asks git about them
                        ctx.session.removed_elsewhere += map(str, folder.removed)
                    _say_abandoned(ctx, progress, abandoned)
            _say_undone(ctx, progress)
            ctx.session.finish_sharing()  # uploads are done (or given up) before it returns
            failpoint("report")
            # Imported here, after the model: the report's modules cost 0.02 s of the start.
            from mjcfbuild.engine.report import record_warnings, write_report, write_stats

            record_warnings(ctx, [task["name"] for task in (*planning, *tasks)])
            if model_built and ctx.robot_path.exists():
                write_report(ctx)
            write_stats(ctx)
    finally:
        # A failed or interrupted build wrote files too: clean must know them. The targets
        # of tasks that ran or were intact hold what the build wrote; the others may not.
        done = {*progress.names(RAN), *progress.names(UP_TO_DATE)}
        every = [*planning, *tasks]
        vouched = [target for task in every if task["name"] in done for target in task["targets"]]
        owned = [target for task in every if task["name"] not in done for target in task["targets"]]
        written.record(ctx, [*vouched, *ctx.session.written], owned)
    if ctx.session.cache_grew:
        _prune_cache(ctx)
    result.engine_log = doit_output if result.errors else ""
    # The build stage makes the planning tasks again (to see them up to date): one of each.
    return list({task["name"]: task for task in (*planning, *tasks)}.values())


def _say_removed(
    ctx: BuildContext, progress: Progress, removed: list[Path], kept: list[Path]
) -> None:
    """Say which files of the model under its old name the build removed, and which it kept
    as edited: a user looking for them must not think them lost, nor current."""
    if not (removed or kept) or progress.quiet:
        return
    now = ", ".join([ctx.label(ctx.robot_path), ctx.label(ctx.scene_path)])
    progress.clear()
    if removed:
        progress.stream.write(
            f"{progress.prefix}mjcfbuild: removed {', '.join(ctx.label(p) for p in removed)}: "
            f"the model's files under names robot.yaml no longer gives (now {now})\n"
        )
    if kept:
        progress.stream.write(
            f"{progress.prefix}mjcfbuild: kept {', '.join(ctx.label(p) for p in kept)}: "
            f"edited since a build wrote it, under a name robot.yaml no longer gives (now "
            f"{now}); no build keeps it current\n"
        )
    progress.stream.flush()


def _say_off(ctx: BuildContext, progress: Progress, leftovers: list[Leftover]) -> None:
    """Say which files of outputs robot.yaml no longer asks for the build removed, and which
    it kept; the removed ones join what ``--fail-on-change`` asks git about."""
    from mjcfbuild.engine.outputs_off import say

    for item in leftovers:
        ctx.session.removed_elsewhere += map(str, item.removable)
        if progress.quiet or not (item.removable or item.kept or item.history):
            continue
        progress.clear()
        progress.stream.write(f"{progress.prefix}mjcfbuild: {say(ctx, item)}\n")
        progress.stream.flush()


def _say_abandoned(ctx: BuildContext, progress: Progress, abandoned: list[Abandoned]) -> None:
    """Say which earlier output folders of robot.yaml the build emptied, and what of the
    user's it kept there."""
    for folder in abandoned:
        if progress.quiet or not (folder.removed or folder.kept):
            continue
        count = len(folder.removed)
        said = f"removed {count} file{'s' if count != 1 else ''} a build wrote in"
        kept = ""
        if folder.kept:
            shown = ", ".join(ctx.label(path) for path in folder.kept[:3])
            more = f" and {len(folder.kept) - 3} more" if len(folder.kept) > 3 else ""
            kept = f"; kept {shown}{more} (not written by a build, or edited since)"
        progress.clear()
        progress.stream.write(
            f"{progress.prefix}mjcfbuild: {said} {ctx.label(folder.folder)}/, "
            f"{ctx.manifest_label}'s output folder before (now {ctx.label(ctx.out_dir)}/)"
            f"{kept}\n"
        )
        progress.stream.flush()


def _say_undone(ctx: BuildContext, progress: Progress) -> None:
    """Name the outputs holding bytes git has in HEAD but no build here wrote (a hand edit
    committed, another build's model pulled) that the build wrote over: git has them, but the
    user must learn they are no longer in the folder."""
    from mjcfbuild.fsutil import md5_file

    undone = []
    for name, digest in ctx.session.committed_edits.items():
        try:
            if md5_file(ctx.out_dir / name) != digest:
                undone.append(name)
        except OSError:
            undone.append(name)  # removed: a stale asset, or the old name's model
    if not undone or progress.quiet:
        return
    progress.clear()
    conflicts = [name for name in undone if name in ctx.session.conflicts]
    held = [name for name in undone if name not in ctx.session.conflicts]
    if held:
        names = ", ".join(ctx.label(ctx.out_dir / name) for name in held)
        progress.stream.write(
            f"{progress.prefix}mjcfbuild: wrote over {names}, which held bytes git has in "
            "HEAD but no build here wrote (`git diff` shows what the build changed; keep a "
            "tuning in robot.yaml)\n"
        )
    if conflicts:
        names = ", ".join(ctx.label(ctx.out_dir / name) for name in conflicts)
        progress.stream.write(
            f"{progress.prefix}mjcfbuild: wrote over {names}, which held a merge conflict "
            "(its markers): the built model resolves it (`git add` it)\n"
        )
    progress.stream.flush()


def _model_tasks(ctx: BuildContext, tasks: list[dict]) -> list[str]:
    """The tasks that write the model and its assets, and the scene."""
    written = {str(ctx.robot_path), str(ctx.scene_path)}
    return [task["name"] for task in tasks if written & set(task["targets"])]


def _after_the_model(tasks: list[dict], model_tasks: list[str]) -> None:
    """Have every task the model does not need start only once all of it (assets and scene
    included) is written, so that none of them - the check and its reference kinematics,
    previews, tuning report, page - takes a core from the model or holds back the line
    announcing it. Order only: a ``task_dep`` makes no task rerun."""
    made_by = {target: task["name"] for task in tasks for target in task["targets"]}
    needs = {
        task["name"]: {*task.get("task_dep", []), *filter(None, map(made_by.get, task["file_dep"]))}
        for task in tasks
    }
    needed, pending = set(model_tasks), list(model_tasks)
    while pending:
        for name in needs.get(pending.pop(), ()):
            if name not in needed:
                needed.add(name)
                pending.append(name)
    for task in tasks:
        if task["name"] not in needed:
            task["task_dep"] = list(dict.fromkeys([*task.get("task_dep", []), *model_tasks]))


def _model_line(ctx: BuildContext) -> str:
    """The line that says the model can be opened, naming its files from the current folder
    (absolute where that is shorter than climbing out of it)."""

    def shown(path: Path) -> str:
        relative = os.path.relpath(path)
        return str(path) if relative.startswith("..") else relative

    return f"mjcfbuild: model ready: {shown(ctx.robot_path)}, {shown(ctx.scene_path)}"


def _summarise(
    result: BuildResult, progress: Progress, ctx: BuildContext, started: float, tasks: list[dict]
) -> None:
    result.ran = progress.names(RAN)
    result.up_to_date = progress.names(UP_TO_DATE)
    result.blocked = progress.names(BLOCKED)
    result.warnings = _shown_warnings(ctx, progress, tasks)
    result.slowest = progress.slowest()
    result.seconds = max(time.perf_counter() - started, 1e-9)


def _shown_warnings(ctx: BuildContext, progress: Progress, tasks: list[dict]) -> list[str]:
    """The warnings a build shows: those of every one of ``tasks`` it ran or found up to date
    (as the task gave them when it last ran, like the report), in graph order, then the
    build's own (the product sharing's). So a build that found the folder up to date says
    what the no-op fast path says, and a rebuild still shows what the tasks it did not run
    warned of; a task that failed or never ran shows nothing. Without ``tasks`` (a build
    stopped before or while it planned, or by a file it could not write), the warnings of the
    tasks that ran."""
    from mjcfbuild.engine.report import build_warnings, task_warnings

    done = {*progress.names(RAN), *progress.names(UP_TO_DATE)}
    if tasks:
        given = task_warnings(ctx, [task["name"] for task in tasks if task["name"] in done])
    else:
        given = dict(ctx.session.task_warnings)
    return placed_warnings(
        ctx, [*(w for warnings in given.values() for w in warnings), *build_warnings(ctx)]
    )


def _model_warnings(ctx: BuildContext) -> list[str]:
    """The warnings of the tasks that made the outputs, whenever they ran, as the console
    shows them (placed in the xacro source): what a no-op prints for the model."""
    from mjcfbuild.engine.report import recorded_warnings

    return recorded_warnings(ctx)


def _run_stage(
    ctx: BuildContext, tasks: list[dict], progress: Progress, result: BuildResult
) -> str:
    interrupts.check()
    code, output = run_doit(ctx, tasks, progress, ["run"])
    interrupts.check()  # doit stops handing out tasks at a KeyboardInterrupt: none failed
    failed = progress.names(FAILED)
    for name in failed:
        error = ctx.session.failures.get(name)
        if error is None:
            message = progress.failure_messages.get(name, "failed")
            error = MjcfbuildError(f"{name}: {_first_line(message)}")
            ctx.session.failures[name] = error
        if ctx.manifest_file is not None:
            error = pinpoint(error, ctx.manifest_label, ctx.manifest_file)
        xacro = ctx.source_path if ctx.source_kind == "xacro" else None
        for urdf in expanded_urdfs(ctx):  # where their elements were written (xacro)
            top = xacro if urdf == ctx.state(SOURCE_URDF) else None
            point_at_source(error, urdf, ctx.label(urdf), ctx.base_dir, top)
        if error not in result.errors:
            result.errors.append(error)
    if code != 0 and not result.errors:
        message = (
            progress.failure_messages.get("(doit)") or output.strip() or f"doit exited with {code}"
        )
        error = _database_failure(ctx)
        result.errors.append(error or MjcfbuildError(f"build engine error: {_first_line(message)}"))
    return output


def _database_failure(ctx: BuildContext) -> MjcfbuildError | None:
    """The error naming doit's database when writing it is what failed (a full disk, a
    read-only folder): doit says "database or disk is full", that the file may be corrupted
    and should be removed, or nothing at all (exit 3). A small write beside it tells."""
    database = ctx.state(DATABASE)
    probe = database.with_name(f".space-probe.{os.getpid()}{TEMP_SUFFIX}")
    try:
        with open(probe, "wb") as handle:
            handle.write(bytes(1 << 16))  # an SQLite transaction writes pages and a journal
            handle.flush()
            os.fsync(handle.fileno())
    except OSError as exc:
        return write_failure(exc, file=ctx.label(database))
    finally:
        with contextlib.suppress(OSError):
            probe.unlink(missing_ok=True)
    return None


def _first_line(text: str) -> str:
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[-1] if lines else text


def prepare_state(ctx: BuildContext) -> None:
    """The state folder ignores itself in git; stdin input is stored; stale temp files go."""
    from mjcfbuild.ownership import STATE_IGNORE

    write_if_changed(ctx.state(".gitignore"), STATE_IGNORE)
    remove_stale_temp_files(ctx.out_dir)
    remove_stale_temp_files(ctx.state_dir)
    if ctx.manifest.source.description == "-":
        data = sys.stdin.buffer.read()
        if not data.strip():
            # Said here: later, the error would name the state folder's copy of stdin.
            raise InputError(
                "the robot description read from standard input is empty",
                file="<stdin>",
                hint="pipe the URDF into the command, as in: ... < robot.urdf",
            )
        write_if_changed(ctx.source_path, data)


def _prune_cache(ctx: BuildContext) -> None:
    """Keep the shared cache under its size cap after a build added to it."""
    from mjcfbuild.products.store import ProductStore

    settings = ctx.cache_settings()
    ProductStore(Path(settings["folder"]), settings["max_bytes"]).prune_if_full()


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
