"""Named points where a test can stop a build abruptly: ``MJCFBUILD_FAILPOINT=point:action``.

The interruption tests kill real builds at chosen moments (during mesh conversion, during a
decomposition, between publishing assets and writing the model, in the middle of writing a
file) to prove the next build recovers. ``action`` is ``kill`` (SIGKILL to the build and the
worker, as ``kill -9`` would), ``interrupt`` (SIGINT to the build, as Ctrl-C would),
``terminate`` (SIGTERM to the build, as ``kill`` or a CI runner cancelling a job would),
``interrupt-swallowed`` (SIGINT to the build process reaching the point, whose
``KeyboardInterrupt`` is then caught there, as a finalizer or code that catches everything
would: mjcfbuild.interrupts), ``raise`` (an unexpected exception, as a bug in mjcfbuild would
raise) or ``stop`` (SIGSTOP to the process that reached the point, so that a test can look at
what it holds there and go on with SIGCONT). Without the variable, a failpoint does nothing.
"""

from __future__ import annotations

import os
import signal
import time

VARIABLE = "MJCFBUILD_FAILPOINT"
BUILD_PID = "MJCFBUILD_BUILD_PID"
ONCE_DIR_VARIABLE = "MJCFBUILD_FAILPOINT_ONCE_DIR"


def failpoint(name: str, spec: str | None = None, once_dir: str | None = None) -> None:
    """Stop the build here if the environment (or ``spec``, sent to a cluster worker) asks.

    An action ending in ``-once`` (``kill-once``) acts only the first time any process reaches
    the point: a marker file in ``once_dir`` (default ``$MJCFBUILD_FAILPOINT_ONCE_DIR``) records it.
    """
    spec = spec if spec is not None else os.environ.get(VARIABLE)
    if not spec:
        return
    for item in spec.split(","):
        point, _, action = item.rpartition(":")
        if point != name:
            continue
        if action.endswith("-once"):
            action = action.removesuffix("-once")
            if not _first_time(name, once_dir or os.environ.get(ONCE_DIR_VARIABLE, "")):
                continue
        if action == "raise":
            raise RuntimeError(f"failpoint {name}")
        if action == "stop":
            os.kill(os.getpid(), signal.SIGSTOP)
            return
        if action == "interrupt-swallowed":
            try:
                os.kill(os.getpid(), signal.SIGINT)
                time.sleep(2.0)  # the handler runs in the main thread by then
            except KeyboardInterrupt:
                pass
            return
        build = int(os.environ.get(BUILD_PID, os.getpid()))
        if action in ("interrupt", "terminate"):
            os.kill(build, signal.SIGINT if action == "interrupt" else signal.SIGTERM)
            time.sleep(2.0)  # let the build react while this step is still busy
            return
        os.kill(build, signal.SIGKILL)
        os.kill(os.getpid(), signal.SIGKILL)


def _first_time(name: str, folder: str) -> bool:
    """Whether this is the first time a process reached ``name`` (marker in ``folder``)."""
    try:
        os.close(os.open(os.path.join(folder, f"failpoint-{name}"), os.O_CREAT | os.O_EXCL))
    except FileExistsError:
        return False
    return True
