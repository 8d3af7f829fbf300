"""What changes while one build runs: its workers, its hash cache, its product sharing, and
what its tasks reported (failures, warnings, timings, notes).

A :class:`~mjcfbuild.engine.context.BuildContext` is the build's configuration and never
changes; each context gets a new session, so a second build in one process (``replace`` of a
context, or a new one) starts from nothing. doit runs tasks in threads: the lists and dicts
here are only appended to or set per task, and the sharing service is started under a lock.
"""

from __future__ import annotations

import re
import threading
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mjcfbuild.errors import InternalError, MjcfbuildError, write_failure
from mjcfbuild.families import assemble, selfcollision

# The steps that compile the built model with MuJoCo: each runs where one ran before, or where
# the model's meshes were warmed while it was assembled, and finds them processed (check.loading).
from mjcfbuild.families.registry import COMPILES_MODEL

ASSEMBLE = assemble.FAMILY.step
SELFCOLLISION = selfcollision.FAMILY.step
WARM = "mjcfbuild.steps.warm:run"

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext
    from mjcfbuild.engine.workers import WorkerPool
    from mjcfbuild.graph.hashes import HashCache
    from mjcfbuild.sharing.coordinator import ProductSharing


class BuildSession:
    """The state of one build of one :class:`BuildContext`."""

    def __init__(self, ctx: BuildContext) -> None:
        self.ctx = ctx
        self.failures: dict[str, MjcfbuildError] = {}
        self.warnings: list[str] = []
        self.task_warnings: dict[str, list[str]] = {}  # what each task that ran warned of
        self.timings: dict[str, float] = {}
        self.notes: dict[str, str] = {}  # task -> a word for the progress line ("from cache")
        self.written: set[str] = set()  # files this build wrote (engine.written records them)
        self.removed_elsewhere: list[str] = []  # outside the output folder (earlier folders)
        # Outputs edited since a build wrote them whose edit git has in HEAD, each with the MD5
        # of the edit: the build may write over them, and says so (engine.guard finds them).
        self.committed_edits: dict[str, str] = {}
        self.conflicts: set[str] = set()  # those of them held for their conflict markers
        self.cache_grew = False  # a product was stored: the cache may need pruning
        self.cache_report: dict[str, Any] | None = None
        self._hashes: HashCache | None = None
        self._pool: WorkerPool | None = None
        self._sharing: ProductSharing | None = None
        self._sharing_lock = threading.Lock()
        self._pool_lock = threading.Lock()
        self._closed = False
        # Whether the output folder had no build before (no worker has its meshes processed).
        self.first_build = False
        # The state folder this build took (device, inode): one removed while it ran is gone
        # or another folder at the end (engine.runner).
        self.state_folder: tuple[int, int] | None = None
        # The threads running a step in this process (doit's), which close() waits for.
        self._here: set[int] = set()
        self._here_done = threading.Condition()

    @property
    def hashes(self) -> HashCache:
        """The :class:`HashCache` of the output folder."""
        if self._hashes is None:
            from mjcfbuild.graph.hashes import HashCache

            state = self.ctx.state_dir
            self._hashes = HashCache(state / "hashes.json" if state.is_dir() else None)
        return self._hashes

    @property
    def sharing(self) -> ProductSharing:
        """The :class:`ProductSharing` of this build, made when the first product is needed."""
        with self._sharing_lock:
            if self._sharing is None:
                from mjcfbuild.sharing.coordinator import ProductSharing

                choice = self.ctx.sharing_choice
                self._sharing = ProductSharing(
                    choice.remote,
                    choice.executor,
                    self.warnings.append,
                    self.ctx.environ,
                    self.ctx.step_timeout,
                )
            return self._sharing

    def finish_sharing(self) -> None:
        """Wait for uploads to the remote cache and keep what was shared for the report."""
        with self._sharing_lock:
            sharing, self._sharing = self._sharing, None
        if sharing is not None:
            self.cache_report = sharing.finish(Path(self.ctx.cache_settings()["folder"]))

    def run_step(self, step: str, payload: dict, *, task: str, in_worker: bool) -> dict:
        """Run a build step, in a worker process or here, and return its result.

        Mesh conversions and decompositions go through :class:`ProductSharing` first, which
        may fetch their product from the remote cache or compute it on a cluster.
        """
        from mjcfbuild import interrupts
        from mjcfbuild.sharing.coordinator import SHARED_STEPS

        interrupts.check()  # no step starts once SIGINT came, even if doit went on
        kind = SHARED_STEPS.get(step)
        if kind is None:
            return self._run_step(step, payload, task, in_worker)
        sharing = self.sharing
        origin = sharing.before(kind, payload, task)
        result = self._run_step(step, payload, task, in_worker)
        sharing.after(kind, payload, origin, result)
        return result

    def _run_step(self, step: str, payload: dict, task: str, in_worker: bool) -> dict:
        if not in_worker:
            import importlib

            thread = threading.get_ident()
            try:
                with self._here_done:
                    self._here.add(thread)
                module_name, _, function_name = step.partition(":")
                function = getattr(importlib.import_module(module_name), function_name)
                result: dict = function(payload)
                return result
            finally:
                with self._here_done:
                    self._here.discard(thread)
                    self._here_done.notify_all()
        self.ctx.logs_dir.mkdir(parents=True, exist_ok=True)
        log = self.ctx.logs_dir / (re.sub(r"[^A-Za-z0-9_.-]+", "-", task) + ".log")
        affinity = str(self.ctx.robot_path) if step in COMPILES_MODEL else None
        started = None
        if step == SELFCOLLISION and self.first_build:
            started = partial(self._prepare_assembly_worker, payload)
        elif step == ASSEMBLE and self.checks:
            started = partial(self._warm_second_worker, payload)
        try:
            return self._workers().run(
                step, payload, task, log, self.ctx.step_timeout, affinity, started
            )
        finally:
            if step == SELFCOLLISION:  # a warm-up not started by now would hold up the assembly
                self._workers().forget_warm_up()

    def _prepare_assembly_worker(self, matrix_payload: dict) -> None:
        """While the self-collision matrix is computed, an idle worker imports the assembly's
        modules and processes the model's mesh products, drawn ones included, so that the
        assembly, which waits for the matrix, starts there with nothing left to load (g1: the
        assembly 0.52-0.55 s instead of 0.75). The other worker would otherwise wait idle, and
        the matrix's worker has processed only the collision meshes. Called once the matrix
        has its worker, so the warm-up never takes it; where the other worker is still busy
        (converting a drawn mesh), it takes that one when it falls idle before the matrix
        ends. The products are those converted by now: a drawn mesh converting beside the
        matrix is left to the assembly."""
        from mjcfbuild.steps.payloads import SelfCollisionPayload, WarmPayload

        request = SelfCollisionPayload.from_dict(matrix_payload)
        products = self.ctx.products_dir
        folders = [str(f) for f in products.iterdir() if f.is_dir()] if products.is_dir() else []
        folders += [d.folder for d in request.decompositions]
        module = ASSEMBLE.partition(":")[0]
        warm = WarmPayload(folders=sorted(folders), modules=["mujoco", module]).to_dict()
        self._workers().warm_for(
            str(self.ctx.robot_path),
            WARM,
            warm,
            self.ctx.step_timeout,
            prepares=(module,),
            until_idle=True,  # the other worker may still be converting a drawn mesh
        )

    def _warm_second_worker(self, assemble_payload: dict) -> None:
        """While the model is assembled, an idle worker processes its mesh products, so that
        the check and the previews can both run in a worker that has them."""
        from mjcfbuild.steps.payloads import AssemblePayload, WarmPayload

        request = AssemblePayload.from_dict(assemble_payload)
        folders = [*request.product_dirs.values(), *(d.folder for d in request.decompositions)]
        warm = WarmPayload(folders=sorted(folders)).to_dict()
        # In a first build the idle worker ran the matrix: it holds the model, but with only
        # the collision meshes processed.
        self._workers().warm_for(
            str(self.ctx.robot_path),
            WARM,
            warm,
            self.ctx.step_timeout,
            holders_too=self.first_build,
        )

    def _workers(self) -> WorkerPool:
        with self._pool_lock:  # doit's threads may ask for the first worker together
            if self._pool is None:
                from mjcfbuild.engine.workers import WorkerPool

                self._pool = WorkerPool(self.ctx.jobs, self.ctx.base_dir, self.ctx.logs_dir)
            return self._pool

    def warm_workers(self, first_build: bool) -> None:
        """Start worker processes now, unless the build adopted some (:meth:`adopt`) or this
        is the folder's first build; they import the steps' modules while they wait: two (see
        :func:`~mjcfbuild.engine.workers.rebuild_preloads`). A step goes to an idle worker
        that preloads its module (see WorkerPool)."""
        from mjcfbuild.engine.workers import rebuild_preloads

        self.first_build = first_build
        if self._pool is not None:
            return  # adopted: the command started them (mjcfbuild.engine.early)
        if first_build:
            # A first build's workers start when its first step needs one, unless the command
            # started them with the mesh step's and the model steps' modules
            # (engine.early.first_build_workers).
            # Started here, importing what the check and its URDF reader use, they took CPU
            # from the mesh steps: the model came 0.07-0.28 s later on the example arm, panda,
            # go1 and g1, and the whole build no sooner (bench/edit_times.py --bare).
            return
        first, second = rebuild_preloads(self.checks)
        self._workers().warm_in_background((first, 1, None), (second, 2, None))

    @property
    def checks(self) -> bool:
        """Whether this build checks the model (and draws its previews)."""
        return self.ctx.run_check and self.ctx.manifest.check.enabled

    def adopt(self, pool: WorkerPool) -> bool:
        """Use ``pool`` (started before the manifest was read, mjcfbuild.engine.early) as
        this build's workers, if it was started for this build's folder and job count;
        whether it was. A pool not adopted is the caller's to close."""
        with self._pool_lock:
            if self._pool is not None or pool.cwd != self.ctx.base_dir:
                return False
            if pool.size != max(1, self.ctx.jobs):
                return False
            pool.log_dir = self.ctx.logs_dir
            self._pool = pool
            return True

    def record_failure(self, task: str, error: BaseException) -> MjcfbuildError:
        """Remember why ``task`` failed, as a :class:`MjcfbuildError`."""
        if not isinstance(error, MjcfbuildError):
            import traceback

            error = write_failure(error) or InternalError(
                f"{task}: {type(error).__name__}: {error}",
                details="".join(traceback.format_exception(error)),
            )
        self.failures[task] = error
        return error

    def close(self) -> None:
        """Stop workers, finish uploads, wait for the steps running in this process and save
        the hash cache; once (the build calls it under its folder's lock; a later call must
        not write the hash cache unlocked)."""
        if self._closed:
            return
        self._closed = True
        self.finish_sharing()
        if self._pool is not None:
            self._pool.close()
            self._pool = None
        # After an interrupted stage, doit's threads may still be running a step of their
        # own here: it finishes (its files are written atomically) before the build lets go
        # of the folder, instead of writing after it, or dying half-way as the process ends.
        # A second Ctrl-C stops the wait, and so does the step time limit: nothing waited for
        # under the lock waits without one.
        # This thread's own step (with -j 1 doit runs steps here) has ended: the interrupt
        # came through it, whatever the set says.
        this = threading.get_ident()
        with self._here_done:
            self._here_done.wait_for(lambda: not self._here - {this}, timeout=self.ctx.step_timeout)
        if self._hashes is not None:
            if self._hashes.path is None and self.ctx.state_dir.is_dir():
                self._hashes.path = self.ctx.state("hashes.json")
            self._hashes.save()
