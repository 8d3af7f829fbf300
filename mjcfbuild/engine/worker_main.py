"""A worker process: runs build steps sent by the :class:`WorkerPool`, one at a time.

Steps that run C++ code (mesh loading, CoACD, MuJoCo's compiler) run here so a crash kills
this process, not the build. The protocol is one JSON line per request and per reply on a
private copy of stdout; file descriptors 1 and 2 are pointed at the step's log file while it
runs, so anything the C++ libraries print ends up there instead of corrupting the protocol.

While it waits for its first requests, a worker imports the heavy modules the pool names
(``MJCFBUILD_WORKER_PRELOAD``), one at a time and only while no request is waiting, so a
request is held up by at most one import and later steps find them loaded.
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
from collections.abc import Iterator


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


def _preload(module: str) -> None:
    """Import ``module`` now; a module that fails to import is left to the step that needs it."""
    with contextlib.suppress(Exception):  # the step that imports it reports the error
        importlib.import_module(module)


def requests(stdin: int, preload: list[str]) -> Iterator[bytes]:
    """Request lines read from the file descriptor ``stdin``; between them, while none is
    waiting, the next module of ``preload`` is imported (and removed from the list)."""
    buffer = b""
    while True:
        while b"\n" not in buffer:
            if preload and not select.select([stdin], [], [], 0)[0]:
                _preload(preload.pop(0))
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
    for line in requests(sys.stdin.fileno(), preload):
        reply = _run(json.loads(line))
        protocol.write(json.dumps(reply) + "\n")
        protocol.flush()
    # Stdin closed (the build process is gone). Replies and logs are flushed; the
    # interpreter's teardown (unloading MuJoCo, trimesh, numpy) would take 0.2-0.4 s.
    os._exit(0)


if __name__ == "__main__":
    main()
