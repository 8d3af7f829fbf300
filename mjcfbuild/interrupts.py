"""Ctrl-C (SIGINT) and SIGTERM: a command either reaches stops with exit code 128 + the
signal's number (130, 143), saying "interrupted" in one line and never reporting success.

SIGTERM (``kill``, a CI runner cancelling a job, ``timeout``, systemd) is handled as Ctrl-C
is: the build stops handing out steps, records the ones that finished and lets go of its
folder, so that the next build redoes none of them. Before, SIGTERM ended the process where
it stood, with no line and the build database unsaved.

A process that starts with a signal ignored keeps ignoring it, as Python and make do: a shell
script starts the commands it puts in the background (``mjcfbuild build &``) so, for Ctrl-C at
the terminal to stop the script's foreground command and leave those running, and whatever
started the build asked for that (``nohup`` likewise for SIGHUP, which is not handled here).
(Such a build sent SIGINT runs to its end; that is what the interruption tests once saw in a
run started in the background, before their builds were started with SIGINT at its default,
tests/conftest.py.) Any other process gets :func:`_interrupted` (:func:`handle_signals`).

A ``KeyboardInterrupt`` can also be lost after it is raised: raised while the main thread runs
a finalizer (a ``__del__``, a generator the garbage collector closes) it is printed as
ignored, and code that catches every exception carries on. The handler therefore also records
the signal, and the build checks the record (:func:`check`) before each step, at the start and
end of each stage and before it reports success or writes its no-op stamp.
"""

from __future__ import annotations

import signal
from types import FrameType

SIGNALS = (signal.SIGINT, signal.SIGTERM)
"""The signals that stop a command as Ctrl-C does."""

INTERRUPTED_CODE = 128 + signal.SIGINT  # 130: mjcfbuild.errors.EXIT_INTERRUPTED

_received = 0  # the number of the first such signal since :func:`forget`; 0: none


def handle_signals() -> None:
    """Have SIGINT and SIGTERM raise ``KeyboardInterrupt`` in this process and be remembered,
    each unless the process started with it ignored; from the main thread of a process that is
    mjcfbuild's command."""
    for number in SIGNALS:
        if signal.getsignal(number) is not signal.SIG_IGN:
            signal.signal(number, _interrupted)


def _interrupted(signum: int, frame: FrameType | None) -> None:
    global _received
    _received = _received or signum
    raise KeyboardInterrupt


def forget() -> None:
    """Forget a signal received before (a command run again in the same process)."""
    global _received
    _received = 0


def received() -> bool:
    """Whether SIGINT or SIGTERM reached this process since :func:`forget`."""
    return _received != 0


def terminated() -> bool:
    """Whether the signal that reached this process was SIGTERM (not Ctrl-C)."""
    return _received == signal.SIGTERM


def exit_code() -> int:
    """The exit code of a command stopped by a signal: 128 + its number, as a shell reports a
    process that signal ended (130 for Ctrl-C, 143 for SIGTERM); 130 for a
    ``KeyboardInterrupt`` no handler of ours raised."""
    return 128 + _received if _received else INTERRUPTED_CODE


def check() -> None:
    """Raise ``KeyboardInterrupt`` if SIGINT or SIGTERM reached this process, even if the
    ``KeyboardInterrupt`` it raised then was lost on the way."""
    if _received:
        raise KeyboardInterrupt
