"""A pool of worker processes that turns a crash or a hang into an ordinary step failure.

doit runs tasks in threads; each thread hands its step to an idle worker process (started on
demand, up to the job count) and waits for the reply. If the worker dies (a segfault in C++
code) or exceeds its time limit, the step fails with :class:`TaskCrashed` naming the task and
its log, the worker is replaced, and every other task carries on.

A first build, which runs every step, starts all its workers as it begins
(:meth:`WorkerPool.warm`), and each imports the heavy modules of the build steps while it
waits, so that work overlaps the build's planning. Another build starts one worker that
imports MuJoCo and the steps that compile the model (nearly every rebuild runs them), and the
others when a step needs them: an incremental build often runs one or two steps, and
importing what it does not need would only compete with them for the CPU (measured: warming
every worker with every module made a one-joint edit of the example arm 0.8 s slower, one
warm worker makes it 0.3 s faster).

Steps that compile the same model name it as their *affinity*: they go to a worker that ran
one before, where MuJoCo has the model's meshes processed, or one warmed for it
(:meth:`WorkerPool.warm_for`).

Unless resident workers are off, the pool first takes workers an earlier build left waiting
(mjcfbuild.engine.resident), which may hold the model's meshes already, and the workers it
starts stay for the next build when this one lets go of them (:meth:`WorkerPool.close`).
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.engine.worker_main import MESHES_VARIABLE, PRELOAD_VARIABLE, process_state
from mjcfbuild.errors import InternalError, MjcfbuildError, TaskCrashed
from mjcfbuild.failpoints import BUILD_PID
from mjcfbuild.families.registry import CHECK_MODULES  # the report-only families' steps

if TYPE_CHECKING:
    from mjcfbuild.engine.resident import Resident

# What the build steps import, in the order a build needs them: warm workers import these.
# Not trimesh (0.6 s of CPU with the scipy and networkx it imports): binary STL and COLLADA,
# the formats of nearly every description, are read without it; the step imports it if needed.
MESH_MODULES = ("numpy", "lxml.etree", "mjcfbuild.steps.mesh")
MODEL_MODULES = ("mujoco", "mjcfbuild.steps.selfcollision", "mjcfbuild.steps.assemble")


def first_build_preloads() -> tuple[tuple[str, ...], tuple[str, ...]]:
    """What the first two workers of a folder's first build import while it reads the
    manifest and plans: the mesh step's modules, which its first steps need, then MuJoCo
    and, in the first, the self-collision matrix's step, in the second the assembly's. The
    matrix goes to the worker that imported its step, and the other, prepared for the
    assembly while the matrix is computed (mjcfbuild.engine.session), then only processes
    meshes: before, it imported MuJoCo and the assembly's modules there too, and g1's model
    waited for them (about 0.28 s of the 0.75 s that preparation took)."""
    first = (*MESH_MODULES, "mujoco", "mjcfbuild.steps.selfcollision")
    return first, (*MESH_MODULES, "mujoco", "mjcfbuild.steps.assemble")


def rebuild_preloads(checks: bool) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """What the two workers of a build that is not the first import while they wait: the
    first MuJoCo and the steps that compile the model, which nearly every rebuild runs; the
    second the mesh step. If the build checks, both then import the check's and previews'
    modules (light without the URDF reader): the check runs in either, where MuJoCo has the
    model's meshes."""
    if not checks:
        return MODEL_MODULES, MESH_MODULES
    return MODEL_MODULES + CHECK_MODULES, (*MESH_MODULES, "mujoco", *CHECK_MODULES)


# The largest block the C heap serves itself rather than by mmap, and the free space at its
# top it keeps rather than returns (bytes; see worker_environment).
HEAP_BLOCKS = 1 << 30


def worker_environment() -> dict[str, str]:
    """The environment of a worker process of this build."""
    env = dict(os.environ)
    for variable in (PRELOAD_VARIABLE, MESHES_VARIABLE):
        env.pop(variable, None)
    env.setdefault("PYTHONHASHSEED", "0")
    # One thread per worker: -j is the build's CPU budget. CoACD is OpenMP-parallel, and
    # two workers each starting a thread per core would fight over the same cores.
    env.setdefault("OMP_NUM_THREADS", "1")
    # Each MuJoCo compile allocates and frees the model's tens of megabytes. glibc serves
    # blocks that large by mmap and unmaps them when freed, so every compile faulted in and
    # zeroed fresh pages: a third of its time (g1: 0.070 s a compile, 0.044 s from the heap).
    # From the heap, freed pages serve the next compile; a resident worker hands them back
    # while it waits for a build (worker_main._give_back_memory). A C library that refuses
    # the value (other than glibc, or a glibc capping the threshold) keeps its default.
    for variable in ("MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_"):
        env.setdefault(variable, str(HEAP_BLOCKS))
    env[BUILD_PID] = str(os.getpid())
    if sys.platform.startswith("linux"):
        # Offscreen rendering (previews) without a display; must be set before import mujoco.
        env.setdefault("MUJOCO_GL", "egl")
    package_root = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [package_root, env.get("PYTHONPATH")]))
    return env


class _Worker:
    """One worker process and the channel to it: its stdin and stdout when this build
    started it for itself, or a socket when it is resident (mjcfbuild.engine.resident)."""

    def __init__(
        self,
        preload: tuple[str, ...],
        meshes_from: Path | None,
        process: subprocess.Popen | None,
        resident: Resident | None = None,
    ) -> None:
        self.preload = preload
        self.meshes_from = meshes_from
        # The model whose meshes MuJoCo has cached in this process (the affinity of the last
        # step it ran that had one), and the affinity of the step it is running now.
        self.holds: str | None = resident.holds if resident is not None else None
        self.running: str | None = None
        # The step modules a warm-up running here is for, and those one was for (warm_for).
        self.preparing: tuple[str, ...] = ()
        self.prepared: tuple[str, ...] = ()
        self.calling = False
        self.process = process
        self.resident = resident
        if resident is not None:
            self.pid = resident.pid
            self._send_fd = self._receive_fd = resident.connection.fileno()
        else:
            # Both pipes exist: the caller asked for them.
            assert process is not None and process.stdin and process.stdout
            self.pid = process.pid
            self._send_fd, self._receive_fd = process.stdin.fileno(), process.stdout.fileno()
        self._buffer = b""

    @staticmethod
    def start(
        cwd: Path, stderr_log: Path, preload: tuple[str, ...], meshes_from: Path | None
    ) -> _Worker:
        """A worker process of this build's own, which ends with it."""
        env = worker_environment()
        env[PRELOAD_VARIABLE] = ",".join(preload)
        if meshes_from is not None:
            env[MESHES_VARIABLE] = str(meshes_from)
        with open(stderr_log, "ab") as stderr:
            process = subprocess.Popen(
                [sys.executable, "-m", "mjcfbuild.engine.worker_main"],
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=stderr,
                cwd=cwd,
                env=env,
            )
        return _Worker(preload, meshes_from, process)

    def call(self, request: dict, label: str, timeout: float | None) -> dict:
        self.calling = True
        try:
            return self._call(request, label, timeout)
        finally:
            self.calling = False

    def _call(self, request: dict, label: str, timeout: float | None) -> dict:
        data = memoryview((json.dumps(request) + "\n").encode())
        try:
            while data:
                data = data[os.write(self._send_fd, data) :]
        except OSError:
            raise self._died(label, request) from None
        deadline = None if timeout is None else time.monotonic() + timeout
        while b"\n" not in self._buffer:
            wait = None if deadline is None else max(0.0, deadline - time.monotonic())
            ready, _, _ = select.select([self._receive_fd], [], [], wait)
            if not ready:
                self.kill()
                raise TaskCrashed(
                    f"{label} did not finish within {timeout:g} s and was stopped",
                    hint=_log_hint(request),
                )
            try:
                chunk = os.read(self._receive_fd, 1 << 16)
            except OSError:
                chunk = b""
            if not chunk:
                raise self._died(label, request)
            self._buffer += chunk
        line, _, self._buffer = self._buffer.partition(b"\n")
        return json.loads(line)

    def _died(self, label: str, request: dict) -> TaskCrashed:
        if self.process is None:  # a resident worker
            from mjcfbuild.engine.resident import how_it_ended, running

            if running(self.pid):  # it closed the connection: it must not go on
                self.kill()
            how = how_it_ended(self.pid)
        else:
            code = self.process.wait()
            if code < 0:
                try:
                    how = f"crashed ({signal.Signals(-code).name})"
                except ValueError:
                    how = f"was killed by signal {-code}"
            else:
                how = f"exited with code {code}"
        return TaskCrashed(f"{label}: the worker process {how}", hint=_log_hint(request))

    def alive(self) -> bool:
        if self.process is not None:
            return self.process.poll() is None
        from mjcfbuild.engine.resident import running

        return running(self.pid)

    def kill(self) -> None:
        if self.process is not None:
            if self.process.poll() is None:
                self.process.kill()
            self.process.wait()
        else:
            from mjcfbuild.engine.resident import stop

            stop(self.pid)
        if self.resident is not None:
            self.resident.connection.close()

    def let_go(self) -> None:
        """End this build's use of the worker: a resident worker that is not running a step
        waits for the next build; any other is stopped."""
        if self.resident is None or self.calling or not self.alive():
            self.kill()
        else:
            self.resident.connection.close()


def _log_hint(request: dict) -> str | None:
    log = request.get("log")
    if not log:
        return None
    tail = _tail(Path(log))
    return f"log: {log}" + (f"; last output: {tail}" if tail else "")


def _tail(path: Path, limit: int = 200) -> str:
    try:
        text = path.read_bytes()[-4096:].decode("utf-8", "replace")
    except OSError:
        return ""
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return lines[-1][:limit] if lines else ""


@dataclass(frozen=True)
class _WarmUp:
    """A warm-up :meth:`WorkerPool.warm_for` runs on an idle worker."""

    affinity: str
    step: str
    payload: dict
    timeout: float | None
    prepares: tuple[str, ...]
    holders_too: bool

    def fits(self, worker: _Worker) -> bool:
        """Whether ``worker`` may take it: one without the model, or (``holders_too``) one
        holding it that no warm-up prepared."""
        free = worker.holds != self.affinity or (self.holders_too and not worker.prepared)
        return free and worker.alive()


class WorkerPool:
    """Up to ``size`` worker processes, started by :meth:`warm` or when first needed."""

    def __init__(self, size: int, cwd: Path, log_dir: Path) -> None:
        from mjcfbuild.engine.resident import idle_seconds, resident_dir

        self.size = max(1, size)
        self.cwd = cwd
        self.log_dir = log_dir
        # Where resident workers wait (mjcfbuild.engine.resident), or None when they are off.
        self.residents = resident_dir(os.environ) if idle_seconds(os.environ) > 0 else None
        self._key: str | None = None
        self._idle: list[_Worker] = []
        self._started = 0
        self._all: list[_Worker] = []
        self._condition = threading.Condition()
        self._closed = False
        self._steps_waiting = 0  # threads in _acquire waiting for a worker
        self._waiting_warm_up: _WarmUp | None = None  # warm_for's, until a worker falls idle
        self._warming: list[threading.Thread] = []  # warm_in_background's
        self._warming_now = 0  # of them, those still starting workers

    def run(
        self,
        step: str,
        payload: dict,
        label: str,
        log: Path | None,
        timeout: float | None,
        affinity: str | None = None,
        started: Callable[[], None] | None = None,
    ) -> dict:
        """Run ``step`` ("module:function") with ``payload`` in a worker; its result dict.

        Steps that compile the same model give the same ``affinity``: such a step goes to a
        worker that ran one before (MuJoCo has the model's meshes cached there), waiting for
        it while it runs one. ``started`` is called once the step has its worker (to prepare
        another one beside it, :meth:`warm_for`, which must not take the step's). Errors the
        step raises come back as the same :class:`MjcfbuildError` class.
        """
        worker = self._acquire(step.partition(":")[0], affinity)
        healthy = False
        try:
            if started is not None:
                with contextlib.suppress(Exception):  # a later step's head start, never a failure
                    started()
            request = {"step": step, "payload": payload, "log": str(log) if log else None}
            reply = worker.call({**request, "affinity": affinity}, label, timeout)
            healthy = True
        finally:
            self._release(worker, healthy, affinity)
        if reply["ok"]:
            return reply["result"]
        error = MjcfbuildError.from_dict(reply["error"])
        if isinstance(error, InternalError):
            error.details = reply.get("traceback", "") or error.details
        raise error

    def warm(
        self, preload: tuple[str, ...], count: int | None = None, meshes_from: Path | None = None
    ) -> None:
        """Start ``count`` workers now (default: all); each imports ``preload`` (module names)
        until steps come, and then processes the mesh products of the model whose assembly
        report is ``meshes_from`` (see mjcfbuild.engine.worker_main)."""
        limit = self.size if count is None else min(self.size, count)
        while True:
            with self._condition:
                if self._closed or self._started >= limit:
                    return
                self._started += 1
            try:
                worker = self._start(preload, meshes_from)
            except BaseException:
                with self._condition:  # the place is free again: a step starts its own
                    self._started -= 1
                    self._condition.notify_all()
                raise
            with self._condition:
                closed = self._closed
                if closed:  # closed while this one started: close() may have missed it
                    if worker in self._all:
                        self._all.remove(worker)
                else:
                    self._idle.append(worker)
                    self._condition.notify_all()
            if closed:
                worker.let_go()

    def warm_in_background(self, *plan: tuple[tuple[str, ...], int | None, Path | None]) -> None:
        """:meth:`warm` with each ``(preload, count, meshes_from)`` of ``plan`` in turn, in a
        thread: starting a worker process is mostly waiting for it to answer (0.05-0.1 s
        each, a new interpreter more), which this process spends reading the manifest and
        planning instead. A step that needs a worker meanwhile waits for the one starting;
        a worker that cannot start leaves its place to the steps, which start their own."""

        def start_all() -> None:
            try:
                # Whatever stops a start here (a folder it cannot write, a bad MJCFBUILD_*
                # value) stops the build's own start of a worker too, which reports it.
                with contextlib.suppress(Exception):
                    for preload, count, meshes_from in plan:
                        self.warm(preload, count, meshes_from)
            finally:
                with self._condition:
                    self._warming_now -= 1
                    self._condition.notify_all()

        thread = threading.Thread(target=start_all, name="mjcfbuild-workers", daemon=True)
        with self._condition:
            self._warming_now += 1
        try:
            thread.start()
        except RuntimeError:  # no thread to be had: the steps start their workers
            with self._condition:
                self._warming_now -= 1
            return
        self._warming.append(thread)

    def wait_started(self) -> None:
        """Wait until the workers :meth:`warm_in_background` is starting have started (or
        failed to)."""
        for thread in list(self._warming):
            thread.join()

    def _start(self, preload: tuple[str, ...] = (), meshes_from: Path | None = None) -> _Worker:
        worker = None
        if self.residents is not None:
            worker = self._resident(self.residents, preload, meshes_from)
        if worker is None:
            self.log_dir.mkdir(parents=True, exist_ok=True)
            worker = _Worker.start(self.cwd, self.log_dir / "workers.log", preload, meshes_from)
        with self._condition:
            self._all.append(worker)
        return worker

    def _resident(
        self, folder: Path, preload: tuple[str, ...], meshes_from: Path | None
    ) -> _Worker | None:
        """An idle resident worker, or a new one that stays after this build; None if a new
        one could not be started (the build starts one of its own)."""
        from mjcfbuild.engine.resident import claim, spawn, worker_key

        env = worker_environment()
        if self._key is None:
            self._key = worker_key(env)
        hello = {
            "key": self._key,
            "env": env,
            "cwd": str(self.cwd),
            "preload": list(preload),
            "meshes_from": str(meshes_from) if meshes_from is not None else None,
            "state": process_state(),
        }
        resident = claim(folder, self._key, hello)
        if resident is None:
            try:
                resident = spawn(folder, self._key, hello, env)
            except OSError:
                return None
        return _Worker(preload, meshes_from, None, resident)

    def warm_for(
        self,
        affinity: str,
        step: str,
        payload: dict,
        timeout: float | None,
        prepares: tuple[str, ...] = (),
        holders_too: bool = False,
        until_idle: bool = False,
    ) -> bool:
        """Run ``step`` in the background on an idle worker that does not hold ``affinity``
        (``holders_too``: or one that does, but was not prepared by a warm-up), which holds it
        afterwards: it prepares a second worker for the steps that will compile the model (see
        :func:`mjcfbuild.check.loading.warm_meshes`), and those of the modules ``prepares``
        (the warm-up imported them) go to it before a worker that holds the model too.
        Whether a worker took it now. Where none is idle, ``until_idle`` keeps the warm-up for
        the next worker that falls idle while no step waits for one, until
        :meth:`forget_warm_up`; a failure only loses the head start."""
        warm_up = _WarmUp(affinity, step, payload, timeout, prepares, holders_too)
        with self._condition:
            idle = [w for w in self._idle if warm_up.fits(w)]
            if self._closed or not idle:
                self._waiting_warm_up = warm_up if until_idle and not self._closed else None
                return False
            return self._launch(idle[-1], warm_up)

    def forget_warm_up(self) -> None:
        """Drop the warm-up :meth:`warm_for` keeps for a worker to fall idle, if none took it:
        the step it was to run beside has ended."""
        with self._condition:
            self._waiting_warm_up = None

    def _launch(self, worker: _Worker, warm_up: _WarmUp) -> bool:
        """Start ``warm_up`` on the idle ``worker`` (the caller holds the lock)."""
        self._idle.remove(worker)
        worker.running = warm_up.affinity
        worker.preparing = warm_up.prepares

        def warm() -> None:
            healthy = warmed = False
            try:
                request = {"step": warm_up.step, "payload": warm_up.payload}
                request["affinity"] = warm_up.affinity
                warmed = worker.call(request, "warm", warm_up.timeout)["ok"]
                healthy = True
            except MjcfbuildError:  # crashed or too slow: the worker is replaced as usual
                pass
            finally:
                held = warm_up.affinity if warmed else None
                self._release(worker, healthy, held, warm_up.prepares if warmed else ())

        try:
            threading.Thread(target=warm, daemon=True).start()
        except RuntimeError:  # no thread to be had: the worker goes back, prepared for nothing
            self._release(worker, True)
            return False
        return True

    def _acquire(self, module: str, affinity: str | None = None) -> _Worker:
        """A worker for a step of ``module``: the one a warm-up is preparing for it, when that
        is done; else an idle one holding ``affinity`` (preferably preloading ``module``), or,
        if one holding it is busy with its model, that one when it is done; else an idle one,
        preferably preloading ``module``; else a new one if the pool has room; else wait."""
        with self._condition:
            while True:
                if self._closed:
                    raise MjcfbuildError("the build was stopped")
                dead = [worker for worker in self._idle if not worker.alive()]
                for worker in dead:  # died while idle (killed from outside): make room
                    self._idle.remove(worker)
                    self._started -= 1
                if any(module in w.preparing for w in self._all):
                    self._wait()  # it has everything the step loads (warm_for)
                    continue
                holders = [w for w in self._all if affinity and w.holds == affinity]
                ready = [w for w in holders if w in self._idle]
                if not ready and any(w.running == affinity for w in holders):
                    self._wait()  # a compile in a cold worker costs more
                    continue
                ready = (
                    [w for w in ready if module in w.prepared]
                    or [w for w in ready if module in w.preload]
                    or ready
                    or [w for w in self._idle if module in w.preload]
                    or self._idle
                )
                if ready:
                    worker = ready[-1]
                    self._idle.remove(worker)
                    worker.running = affinity
                    return worker
                if self._started < self.size and not self._warming_now:
                    self._started += 1
                    break
                self._wait()  # for a worker, or for the one warm_in_background is starting
        worker = self._start()
        worker.running = affinity
        return worker

    def _wait(self) -> None:
        """Wait for a worker to change state, counted as a step waiting (the caller holds the
        lock): a warm-up kept for an idle worker never takes one a step waits for."""
        self._steps_waiting += 1
        try:
            self._condition.wait()
        finally:
            self._steps_waiting -= 1

    def _release(
        self,
        worker: _Worker,
        healthy: bool,
        affinity: str | None = None,
        prepared: tuple[str, ...] = (),
    ) -> None:
        with self._condition:
            worker.running = None
            worker.preparing = ()
            worker.prepared = prepared or worker.prepared
            if healthy and worker.alive() and not self._closed:
                worker.holds = affinity or worker.holds
                self._idle.append(worker)
                warm_up = self._waiting_warm_up
                if warm_up is not None and not self._steps_waiting and warm_up.fits(worker):
                    self._waiting_warm_up = None
                    self._launch(worker, warm_up)
            else:
                worker.kill()
                self._started -= 1
            self._condition.notify_all()

    def close(self) -> None:
        """Let go of every worker at once: every reply is in and every step's log flushed,
        so nothing is lost. Resident workers wait for the next build; the others stop, even
        if still importing a module they were warmed with, and so does any worker still
        running a step (a warm-up, or a step of a build that was interrupted)."""
        with self._condition:
            self._closed = True
            workers, self._all, self._idle = self._all, [], []
            self._condition.notify_all()
        for worker in workers:
            worker.let_go()
