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
"""

from __future__ import annotations

import contextlib
import importlib
import json
import os
import select
import signal
import sys
import threading
import time
import traceback
from collections.abc import Callable, Iterator
from functools import partial


def _watch_parent(parent: int) -> None:
    """Exit when the build process that started this worker is gone."""
    while True:
        time.sleep(1.0)
        if os.getppid() != parent:
            os._exit(3)


def _run(request: dict) -> dict:
    from mjcfbuild.errors import MjcfbuildError

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
    from pathlib import Path

    from mjcfbuild.check.loading import asset_sources

    for product in sorted(set(asset_sources(Path(report)).values())):
        work.append(partial(_warm, str(product)))


# Mesh files processed while idle, with what identified them then (inode, size, mtime).
_warmed: dict[str, tuple[int, int, int]] = {}


def _identity(path: str) -> tuple[int, int, int] | None:
    try:
        stat = os.stat(path)
    except OSError:
        return None
    return stat.st_ino, stat.st_size, stat.st_mtime_ns


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


def _unseen_change(path: str, warmed: tuple[int, int, int]) -> bool:
    """Whether the file at ``path`` differs from when it was processed (``warmed``) while
    keeping the whole-second time MuJoCo's cache compares."""
    now = _identity(path)
    if now is None or now == warmed:
        return False  # gone: MuJoCo cannot read it either; unchanged: the cache is right
    return now[2] // 1_000_000_000 == warmed[2] // 1_000_000_000


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


def main() -> None:
    """Serve requests from stdin until it closes."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the build process decides about Ctrl-C
    threading.Thread(target=_watch_parent, args=(os.getppid(),), daemon=True).start()
    protocol = os.fdopen(os.dup(1), "w", buffering=1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.close(devnull)
    preload = [name for name in os.environ.get(PRELOAD_VARIABLE, "").split(",") if name]
    idle = idle_work(preload, os.environ.get(MESHES_VARIABLE))
    for line in requests(sys.stdin.fileno(), idle):
        drop_mesh_work(idle)
        forget_changed_meshes()
        reply = _run(json.loads(line))
        protocol.write(json.dumps(reply) + "\n")
        protocol.flush()
    # Stdin closed (the build process is gone). Replies and logs are flushed; the
    # interpreter's teardown (unloading MuJoCo, trimesh, numpy) would take 0.2-0.4 s.
    os._exit(0)


if __name__ == "__main__":
    main()
