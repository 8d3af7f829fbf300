"""SIGINT in a process whose command installed mjcfbuild's handler: raised, and remembered
even where the KeyboardInterrupt it raised is caught and lost."""

from __future__ import annotations

import contextlib
import signal

import pytest

from mjcfbuild import interrupts


@pytest.fixture
def handler_restored():
    """Put back the test process's own SIGINT handler and forget any SIGINT received."""
    saved = signal.getsignal(signal.SIGINT)
    yield
    signal.signal(signal.SIGINT, saved)
    interrupts.forget()


def test_sigint_raises_and_is_remembered(handler_restored):
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    interrupts.forget()
    interrupts.handle_sigint()
    with pytest.raises(KeyboardInterrupt):
        signal.raise_signal(signal.SIGINT)
    assert interrupts.received()


def test_a_process_started_with_sigint_ignored_keeps_ignoring_it(handler_restored):
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # as a script's `cmd &` starts it
    interrupts.forget()
    interrupts.handle_sigint()
    signal.raise_signal(signal.SIGINT)
    assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN and not interrupts.received()


def test_a_lost_keyboard_interrupt_is_raised_again_at_the_next_check(handler_restored):
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    interrupts.forget()
    interrupts.handle_sigint()
    interrupts.check()  # nothing received: nothing raised
    with contextlib.suppress(KeyboardInterrupt):  # lost, as in a finalizer would be
        signal.raise_signal(signal.SIGINT)
    with pytest.raises(KeyboardInterrupt):
        interrupts.check()
    interrupts.forget()
    interrupts.check()  # a command run again in this process starts afresh
