"""A worker process: runs build steps sent by the :class:`WorkerPool`, one at a time.

Steps that run C++ code (mesh loading, CoACD, MuJoCo's compiler) run here so a crash kills
this process, not the build. The protocol is one JSON line per request and per reply on a
private copy of stdout; file descriptors 1 and 2 are pointed at the step's log file while it
runs, so anything the C++ libraries print ends up there instead of corrupting the protocol.

While it waits for its first requests, a worker imports the heavy modules the pool names
(``MJCFBUILD_WORKER_PRELOAD``) and then has MuJoCo process the mesh products of the model a
previous build published (``MJCFBUILD_WORKER_MESHES``, its assembly report), one module or
mesh at a time and only while no request is waiting: a request is held up by at most one of
them, and later steps find the modules loaded and, where the meshes are the same, MuJoCo's
cache filled (see mjcfbuild.check.loading). Meshes are processed only until the first request.

A resident worker (``--resident``, mjcfbuild.engine.resident) serves one build on a socket
instead, then waits on a socket of its own for the next build, with the same protocol.
"""

from __future__ import annotations

import contextlib
import importlib
import json
import math
import os
import select
import signal
import socket
import sys
import threading
import time
import traceback
from collections.abc import Callable, Iterator
from functools import partial
from pathlib import Path

from mjcfbuild.filesig import signature


def _watch_parent(parent: int) -> None:
    """Exit when the build process that started this worker is gone."""
    while True:
        time.sleep(1.0)
        if os.getppid() != parent:
            os._exit(3)


def _run(request: dict) -> dict:
    from mjcfbuild.errors import MjcfbuildError, write_failure

    module_name, _, function_name = request["step"].partition(":")
    log = request.get("log")
    saved = os.dup(1), os.dup(2)
    try:
        if log:
            fd = os.open(log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
            os.dup2(fd, 1)
            os.dup2(fd, 2)
            os.close(fd)
        function = getattr(importlib.import_module(module_name), function_name)
        return {"ok": True, "result": function(request["payload"])}
    except MjcfbuildError as exc:
        return {"ok": False, "error": exc.to_dict()}
    except Exception as exc:
        unwritable = write_failure(exc)  # a full disk, a folder it may not write in
        if unwritable is not None:
            return {"ok": False, "error": unwritable.to_dict()}
        return {
            "ok": False,
            "error": {"type": "InternalError", "message": f"{type(exc).__name__}: {exc}"},
            "traceback": traceback.format_exc(),
        }
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        os.close(saved[0])
        os.close(saved[1])


PRELOAD_VARIABLE = "MJCFBUILD_WORKER_PRELOAD"
MESHES_VARIABLE = "MJCFBUILD_WORKER_MESHES"

# What a worker does while no request is waiting, first item first.
IdleWork = list[Callable[[], None]]


def idle_work(preload: list[str], meshes_from: str | None = None) -> IdleWork:
    """Import each module of ``preload``; then, if ``meshes_from`` names an assembly report,
    process the mesh products its model was published from, one item per mesh."""
    work: IdleWork = [partial(_preload, module) for module in preload]
    if meshes_from:
        work.append(partial(_queue_meshes, meshes_from, work))
    return work


def _preload(module: str) -> None:
    """Import ``module`` now; a module that fails to import is left to the step that needs it."""
    with contextlib.suppress(Exception):  # the step that imports it reports the error
        importlib.import_module(module)


def _queue_meshes(report: str, work: IdleWork) -> None:
    from mjcfbuild.check.loading import asset_sources

    for read in sorted({source.read for source in asset_sources(Path(report)).values()}):
        work.append(partial(_warm, str(read)))


# Mesh files processed while idle, with what identified them then (mjcfbuild.filesig).
_warmed: dict[str, list[int]] = {}
_MTIME, _CTIME = 1, 2  # the places of the modification and status-change times in one


def _identity(path: str) -> list[int] | None:
    try:
        return signature(os.stat(path))
    except OSError:
        return None


def _warm(path: str) -> None:
    from mjcfbuild.check.loading import warm_meshes

    identity = _identity(path)
    if identity is not None:
        warm_meshes([path])
        _warmed[path] = identity


def drop_mesh_work(idle: IdleWork) -> None:
    """Remove the meshes from ``idle``, once the build has sent its first step: from then on it
    asks for the meshes it needs (a step compiles them, or step ``warm`` processes them), and
    a large one processed between two steps would hold up the second (go1's trunk: 0.5 s)."""
    idle[:] = [item for item in idle if getattr(item, "func", None) not in (_queue_meshes, _warm)]


def forget_changed_meshes() -> None:
    """Empty MuJoCo's cache if a mesh processed while idle has changed since and MuJoCo
    cannot tell. MuJoCo finds a file in its cache by name and modification time in whole
    seconds (measured with MuJoCo 4.0: a mesh rewritten within the same second compiles as
    the old one; with another second, as the new one), and the build rewrites a product when
    its source changes - possibly within a second of this worker processing the earlier one."""
    if any(_unseen_change(path, identity) for path, identity in _warmed.items()):
        import mujoco

        mujoco.mj_clearCache(mujoco.mj_getCache())
        _warmed.clear()


def note_products(request: dict) -> None:
    """After a step that had MuJoCo process a model's mesh products (assembly, self-collision,
    check, previews, warm-up), remember what identified each product file then, as for meshes
    processed while idle: a product published again at the same path (linked from the shared
    cache, where its time is that of another build) may keep the whole-second time MuJoCo's
    cache compares."""
    payload = request.get("payload")
    if not isinstance(payload, dict):
        return
    folders = list(payload.get("folders") or [])
    folders += list((payload.get("product_dirs") or {}).values())
    folders += [d.get("folder") for d in payload.get("decompositions") or [] if isinstance(d, dict)]
    files: list[str] = []
    for folder in folders:
        if isinstance(folder, str):
            with contextlib.suppress(OSError):
                files += [entry.path for entry in os.scandir(folder) if entry.is_file()]
    report = payload.get("assembly_report")
    if isinstance(report, str) and report:
        from mjcfbuild.check.loading import asset_sources

        for source in asset_sources(Path(report)).values():
            files += [str(path) for path in (source.product, source.copy) if path is not None]
    for name in files:
        identity = _identity(name)
        if identity is not None:
            _warmed[name] = identity


def _unseen_change(path: str, warmed: list[int]) -> bool:
    """Whether the file at ``path`` differs from when it was processed (``warmed``) while
    keeping the whole-second time MuJoCo's cache compares (a rewrite within the second, or
    one that restored the time)."""
    now = _identity(path)
    if now is None or now == warmed:
        return False  # gone: MuJoCo cannot read it either; unchanged: the cache is right
    return now[_MTIME] // 1_000_000_000 == warmed[_MTIME] // 1_000_000_000


def requests(stdin: int, idle: IdleWork) -> Iterator[bytes]:
    """Request lines read from the file descriptor ``stdin``; between them, while none is
    waiting, the next item of ``idle`` is done (and removed from the list)."""
    buffer = b""
    while True:
        while b"\n" not in buffer:
            if idle and not select.select([stdin], [], [], 0)[0]:
                with contextlib.suppress(Exception):  # only a head start: the step decides
                    idle.pop(0)()
                continue
            chunk = os.read(stdin, 1 << 16)
            if not chunk:
                return
            buffer += chunk
        line, _, buffer = buffer.partition(b"\n")
        if line.strip():
            yield line


def serve(
    read_fd: int,
    reply: Callable[[bytes], object],
    idle: IdleWork,
    watch: _ClientWatch | None = None,
) -> Iterator[dict]:
    """Run each request read from ``read_fd`` (watched by ``watch``, if given) and send its
    reply with ``reply``; yields each request after it ran, with ``"ok"`` set to whether it
    succeeded."""
    for line in requests(read_fd, idle):
        drop_mesh_work(idle)
        forget_changed_meshes()
        request = json.loads(line)
        with watch.step() if watch is not None else contextlib.nullcontext():
            answer = _run(request)
        if answer["ok"]:
            note_products(request)
        reply((json.dumps(answer) + "\n").encode())
        request["ok"] = answer["ok"]
        yield request


def main() -> None:
    """Serve requests from stdin until it closes, or, with ``--resident FD FOLDER KEY
    SECONDS``, builds one after another (mjcfbuild.engine.resident)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the build process decides about Ctrl-C
    devnull = os.open(os.devnull, os.O_WRONLY)
    if sys.argv[1:2] == ["--resident"]:
        os.dup2(devnull, 1)
        os.close(devnull)
        fd, folder, key, seconds, most = sys.argv[2:7]
        limits = _Limits(Path(folder), key, float(seconds), int(most))
        _serve_resident(socket.socket(fileno=int(fd)), limits)
        os._exit(0)
    threading.Thread(target=_watch_parent, args=(os.getppid(),), daemon=True).start()
    protocol = os.dup(1)
    os.dup2(devnull, 1)
    os.close(devnull)
    preload = [name for name in os.environ.get(PRELOAD_VARIABLE, "").split(",") if name]
    idle = idle_work(preload, os.environ.get(MESHES_VARIABLE))
    for _ in serve(sys.stdin.fileno(), partial(_write_all, protocol), idle):
        pass
    # Stdin closed (the build process is gone). Replies and logs are flushed; the
    # interpreter's teardown (unloading MuJoCo, trimesh, numpy) would take 0.2-0.4 s.
    os._exit(0)


def _write_all(fd: int, data: bytes) -> None:
    """Write all of ``data`` to ``fd`` (a write to a pipe may take only part of it)."""
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


class _Between:
    """What a resident worker knows of the builds it served."""

    def __init__(self) -> None:
        self.holds: str | None = None  # the model whose meshes MuJoCo has processed here
        self.last_end: float | None = None  # when the last build let go (time.time())


class _Limits:
    """Where a resident worker waits, for which builds, how long and with how many others."""

    def __init__(self, folder: Path, key: str, seconds: float, most: int) -> None:
        self.folder = folder
        self.key = key
        self.seconds = seconds
        self.most = most


def _serve_resident(connection: socket.socket, limits: _Limits) -> None:
    """Serve the build on ``connection``, then wait up to ``limits.seconds`` for the next one
    on a socket in ``limits.folder``, again and again; return when none came in time, when
    the folder is gone, when the build asked it to stop or when it cannot serve a build."""
    from mjcfbuild.engine.resident import answer_seconds, make_room

    between = _Between()
    idle: IdleWork = []
    while True:
        served = _serve_build(connection, limits.key, between, idle)
        connection.close()
        if served is None:
            return  # asked to stop, or cannot serve a build like this one
        if served:
            between.last_end = time.time()
            _code.note()  # what this build imported, as it is now
        drop_mesh_work(idle)  # processing a mesh after the build let go could miss its rewrite
        # Every waiting worker of this user counts, of whatever key: one cap per user.
        if not make_room(limits.folder, limits.key, limits.most, answer_seconds(os.environ)):
            return
        idle.insert(0, _give_back_memory)  # once listening: the next build may come at once
        path = limits.folder / f"{limits.key}-{os.getpid()}.sock"
        waiting = _wait_for_build(path, limits.seconds, idle)
        if waiting is None:
            return
        connection = waiting


class _CodeWatch:
    """The signature (mjcfbuild.filesig) of every module file this process imported, when
    first seen: a module edited in place since (an editable install, a patch to
    site-packages, a ``cp -p`` over it) would not be imported again here, so such a worker
    must not serve another build. A module first seen with a time (modification or status
    change) later than the last look may have changed after it was imported: that counts as
    a change too (slower, never wrong)."""

    def __init__(self) -> None:
        self._seen: dict[str, list[int]] = {}
        self._since = time.time_ns()  # the last look (at first, this process's start)
        self._suspect: str | None = None

    def note(self) -> None:
        """Record the module files imported since the last call."""
        now = time.time_ns()
        for module in list(sys.modules.values()):
            name = getattr(module, "__file__", None)
            if isinstance(name, str) and name not in self._seen:
                identity = _identity(name)
                if identity is not None:
                    self._seen[name] = identity
                    changed = max(identity[_MTIME], identity[_CTIME])
                    if changed >= self._since and self._suspect is None:
                        self._suspect = name
        self._since = now

    def changed(self) -> str | None:
        """A module file that changed since it was recorded (or may have), if any."""
        if self._suspect is not None:
            return self._suspect
        for name, identity in self._seen.items():
            if _identity(name) != identity:
                return name
        return None


_code = _CodeWatch()


def _give_back_memory() -> None:
    """Return what the last build freed to the system while waiting for the next one: the
    C heap keeps freed blocks of MuJoCo's models and the steps' arrays (measured: a worker
    that drew panda's previews held 550-650 MB after the build, 300 MB with this)."""
    import ctypes
    import gc

    gc.collect()
    with contextlib.suppress(OSError, AttributeError):  # glibc only
        ctypes.CDLL("libc.so.6").malloc_trim(0)


def _serve_build(
    connection: socket.socket, key: str, between: _Between, idle: IdleWork
) -> bool | None:
    """Serve the build that connected: True once it let go; False if it went before asking
    anything (the worker waits on); None if this worker is to end (the build asked it to stop,
    its code changed, or it cannot take on the build's process state)."""
    from mjcfbuild.engine.resident import receive_line

    hello = receive_line(connection)
    if hello is None:
        return False
    if hello.get("stop"):
        with contextlib.suppress(OSError):
            connection.sendall((json.dumps({"stopping": os.getpid()}) + "\n").encode())
        return None
    if hello.get("key") != key:
        return False
    if _code.changed() is not None:
        return None  # the build finds another worker, or starts one with the new code
    if not adopt_process_state(hello):
        return None
    try:
        os.chdir(hello["cwd"])
    except OSError:
        return False  # the build's folder is gone: the build starts a worker of its own
    os.environ.clear()
    os.environ.update(hello["env"])
    if between.last_end is not None:
        _keep_or_forget_meshes(between)
    try:
        connection.sendall(
            (json.dumps({"pid": os.getpid(), "holds": between.holds}) + "\n").encode()
        )
    except OSError:
        return True
    idle[:] = idle_work(hello.get("preload", []), hello.get("meshes_from"))
    watch = _ClientWatch(connection)
    try:
        for request in serve(connection.fileno(), connection.sendall, idle, watch):
            if request["ok"] and request.get("affinity"):
                between.holds = request["affinity"]
    except OSError:
        pass  # the build let go while the reply was sent
    finally:
        watch.stop()
    return True


# Resource limits a build's workers share with the build (resource.RLIMIT_<name>).
RLIMITS = ("CORE", "CPU", "DATA", "FSIZE", "NOFILE", "AS", "STACK", "MEMLOCK", "NPROC", "RSS")


def process_state() -> dict:
    """What a worker takes on from the build it serves besides the environment: the file
    mode mask, the nice level and the resource limits."""
    import resource

    umask = os.umask(0)
    os.umask(umask)
    limits = {}
    for name in RLIMITS:
        number = getattr(resource, f"RLIMIT_{name}", None)
        if number is not None:
            limits[name] = list(resource.getrlimit(number))
    return {"umask": umask, "nice": os.getpriority(os.PRIO_PROCESS, 0), "rlimits": limits}


def adopt_process_state(hello: dict) -> bool:
    """Take on the build's file mode mask, nice level and resource limits (``hello``'s
    ``state``, from :func:`process_state`); False when this process cannot (its nice level is
    higher or a hard limit lower than the build's, and an unprivileged process cannot undo
    either): the build then starts a worker that inherits them."""
    import resource

    state = hello.get("state")
    if not isinstance(state, dict):
        return False
    try:
        nice = int(state["nice"])
        if os.getpriority(os.PRIO_PROCESS, 0) != nice:
            os.setpriority(os.PRIO_PROCESS, 0, nice)
        for name, (soft, hard) in dict(state["rlimits"]).items():
            number = getattr(resource, f"RLIMIT_{name}", None)
            if number is None or resource.getrlimit(number) == (soft, hard):
                continue
            if name == "CPU":
                return False  # counts this process's CPU time over every build it served
            resource.setrlimit(number, (int(soft), int(hard)))
        os.umask(int(state["umask"]))
    except (OSError, ValueError, TypeError, KeyError):
        return False
    return True


def _keep_or_forget_meshes(between: _Between) -> None:
    """Empty MuJoCo's cache if this build came within the second the last one ended in.

    MuJoCo tells a cached file by name and modification time in whole seconds. A product the
    last build wrote and compiled, rewritten with other content in the same second, would
    compile as the old one; a rewrite by this build after that second cannot be mistaken.
    Files the user edits are forgotten before they are compiled (mjcfbuild.mjcache)."""
    from mjcfbuild import mjcache

    if time.time() < math.floor(between.last_end or 0.0) + 1:
        between.holds = None
        if "mujoco" in sys.modules:
            import mujoco

            mujoco.mj_clearCache(mujoco.mj_getCache())
    else:
        mjcache.kept_from_earlier_build()


def _wait_for_build(path: Path, seconds: float, idle: IdleWork) -> socket.socket | None:
    """Listen on ``path`` until a build connects (doing ``idle`` work meanwhile) or
    ``seconds`` pass; the socket file is gone again either way, so no second build finds it.
    A worker whose socket file was removed (its folder deleted, or ``workers stop``) can
    never be found again: it ends within a second."""
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        with contextlib.suppress(FileNotFoundError):
            path.unlink()
        listener.bind(str(path))
        listener.listen(4)
        bound = path.lstat()
    except OSError:  # the folder went away: no build could find this worker
        listener.close()
        return None
    deadline = time.monotonic() + seconds
    try:
        while True:
            if idle and not select.select([listener], [], [], 0)[0]:
                with contextlib.suppress(Exception):
                    idle.pop(0)()
                continue
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return None
            if select.select([listener], [], [], min(remaining, ORPHAN_CHECK_SECONDS))[0]:
                connection, _ = listener.accept()
                return connection
            if not _still_there(path, bound):
                return None
    finally:
        with contextlib.suppress(OSError):
            if _still_there(path, bound):
                path.unlink()
        listener.close()  # builds still queued on it see their connection reset


ORPHAN_CHECK_SECONDS = 1.0


def _still_there(path: Path, bound: os.stat_result) -> bool:
    """Whether ``path`` is still the socket file this worker made."""
    try:
        now = path.lstat()
    except OSError:
        return False
    return (now.st_ino, now.st_dev) == (bound.st_ino, bound.st_dev)


class _ClientWatch:
    """Stops the process when the build goes away while a step runs, as a worker of the
    build's own does when its parent is gone: the step must not write on after the build."""

    def __init__(self, connection: socket.socket) -> None:
        self._fd = os.dup(connection.fileno())  # its number stays ours until stop()
        self._running = threading.Event()
        self._stopped = False
        threading.Thread(target=self._watch, daemon=True).start()

    @contextlib.contextmanager
    def step(self) -> Iterator[None]:
        """Watch the build while the block runs."""
        self._running.set()
        try:
            yield
        finally:
            self._running.clear()

    def stop(self) -> None:
        """Stop watching: the build let go. The thread ends on its own, closing its copy of
        the connection; waiting for it could keep the next build waiting."""
        self._stopped = True
        self._running.set()

    def _watch(self) -> None:
        poller = select.poll()
        # The peer's close: POLLRDHUP on Linux; elsewhere a hang-up, when the system says one.
        poller.register(self._fd, getattr(select, "POLLRDHUP", 0) | select.POLLHUP)
        try:
            while True:
                self._running.wait()
                if self._stopped:
                    return
                if poller.poll(250) and self._running.is_set() and not self._stopped:
                    os._exit(3)
        finally:
            os.close(self._fd)


if __name__ == "__main__":
    main()
