"""Named points where a test can stop a build abruptly: ``MJCFBUILD_FAILPOINT=point:action``.

The interruption tests kill real builds at chosen moments (during mesh conversion, during a
decomposition, between publishing assets and writing the model, in the middle of writing a
file) to prove the next build recovers. ``action`` is ``kill`` (SIGKILL to the build and the
worker, as ``kill -9`` would), ``interrupt`` (SIGINT to the build, as Ctrl-C would) or ``raise``
(an unexpected exception, as a bug in mjcfbuild would raise). Without the variable, a failpoint
does nothing.
"""

from __future__ import annotations

import os
import signal
import time

VARIABLE = "MJCFBUILD_FAILPOINT"
BUILD_PID = "MJCFBUILD_BUILD_PID"


def failpoint(name: str) -> None:
    """Stop the build here if the environment asks for it."""
    spec = os.environ.get(VARIABLE)
    if not spec:
        return
    for item in spec.split(","):
        point, _, action = item.rpartition(":")
        if point != name:
            continue
        if action == "raise":
            raise RuntimeError(f"failpoint {name}")
        build = int(os.environ.get(BUILD_PID, os.getpid()))
        if action == "interrupt":
            os.kill(build, signal.SIGINT)
            time.sleep(2.0)  # let the build react while this step is still busy
            return
        os.kill(build, signal.SIGKILL)
        os.kill(os.getpid(), signal.SIGKILL)
