"""Ctrl-C (SIGINT): a command it reaches stops with exit code 130, never reporting success.

A process that starts with SIGINT ignored keeps ignoring it, as Python and make do: a shell
script starts the commands it puts in the background (``mjcfbuild build &``) so, for Ctrl-C at
the terminal to stop the script's foreground command and leave those running, and whatever
started the build asked for that. (Such a build sent SIGINT runs to its end; that is what the
interruption tests once saw in a run started in the background, before their builds were
started with SIGINT at its default, tests/conftest.py.) Any other process gets
:func:`_interrupted` (:func:`handle_sigint`).

A ``KeyboardInterrupt`` can also be lost after it is raised: raised while the main thread runs
a finalizer (a ``__del__``, a generator the garbage collector closes) it is printed as
ignored, and code that catches every exception carries on. The handler therefore also records
the signal, and the build checks the record (:func:`check`) before each step, at the start and
end of each stage and before it reports success or writes its no-op stamp.
"""

from __future__ import annotations

import signal
from types import FrameType

_received = False


def handle_sigint() -> None:
    """Have SIGINT raise ``KeyboardInterrupt`` in this process and be remembered, unless it
    started with SIGINT ignored; from the main thread of a process that is mjcfbuild's
    command."""
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        return
    signal.signal(signal.SIGINT, _interrupted)


def _interrupted(signum: int, frame: FrameType | None) -> None:
    global _received
    _received = True
    raise KeyboardInterrupt


def forget() -> None:
    """Forget a SIGINT received before (a command run again in the same process)."""
    global _received
    _received = False


def received() -> bool:
    """Whether SIGINT reached this process since :func:`forget`."""
    return _received


def check() -> None:
    """Raise ``KeyboardInterrupt`` if SIGINT reached this process, even if the
    ``KeyboardInterrupt`` it raised then was lost on the way."""
    if _received:
        raise KeyboardInterrupt
