"""SIGINT and SIGTERM in a process whose command installed mjcfbuild's handler: raised, and
remembered even where the KeyboardInterrupt it raised is caught and lost."""

from __future__ import annotations

import contextlib
import signal

import pytest

from mjcfbuild import interrupts


@pytest.fixture
def handler_restored():
    """Put back the test process's own SIGINT and SIGTERM handlers and forget any signal
    received."""
    saved = {number: signal.getsignal(number) for number in interrupts.SIGNALS}
    yield
    for number, handler in saved.items():
        signal.signal(number, handler)
    interrupts.forget()


def test_sigint_raises_and_is_remembered(handler_restored):
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    interrupts.forget()
    interrupts.handle_signals()
    with pytest.raises(KeyboardInterrupt):
        signal.raise_signal(signal.SIGINT)
    assert interrupts.received()


def test_a_process_started_with_sigint_ignored_keeps_ignoring_it(handler_restored):
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # as a script's `cmd &` starts it
    interrupts.forget()
    interrupts.handle_signals()
    signal.raise_signal(signal.SIGINT)
    assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN and not interrupts.received()


def test_a_lost_keyboard_interrupt_is_raised_again_at_the_next_check(handler_restored):
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    interrupts.forget()
    interrupts.handle_signals()
    interrupts.check()  # nothing received: nothing raised
    with contextlib.suppress(KeyboardInterrupt):  # lost, as in a finalizer would be
        signal.raise_signal(signal.SIGINT)
    with pytest.raises(KeyboardInterrupt):
        interrupts.check()
    interrupts.forget()
    interrupts.check()  # a command run again in this process starts afresh


def test_sigterm_raises_as_ctrl_c_does_with_its_own_exit_code(handler_restored):
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    interrupts.forget()
    assert interrupts.exit_code() == 130  # a KeyboardInterrupt no signal of ours raised
    interrupts.handle_signals()
    with pytest.raises(KeyboardInterrupt):
        signal.raise_signal(signal.SIGTERM)
    assert interrupts.received() and interrupts.terminated()
    assert interrupts.exit_code() == 143
    with contextlib.suppress(KeyboardInterrupt):  # a second signal: the first one's code
        signal.raise_signal(signal.SIGINT)
    assert interrupts.exit_code() == 143


def test_a_process_started_with_sigterm_ignored_keeps_ignoring_it(handler_restored):
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    interrupts.forget()
    interrupts.handle_signals()
    signal.raise_signal(signal.SIGTERM)
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_IGN and not interrupts.received()


def test_a_signal_python_wraps_in_another_exception_still_ends_as_interrupted(
    handler_restored, monkeypatch, capsys
):
    """A KeyboardInterrupt raised while a class is made (pydantic's models, imported mid-build)
    reaches the command as a RuntimeError: it ended as 'internal error', exit 70."""
    import os

    import mjcfbuild.cli as cli

    def signalled(quiet: bool) -> None:
        class Field:
            def __set_name__(self, owner, name):
                os.kill(os.getpid(), signal.SIGTERM)

        class Model:  # made for its Field's __set_name__
            field = Field()

    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    interrupts.forget()
    interrupts.handle_signals()
    monkeypatch.setattr(cli, "_check_cache_settings", signalled)
    assert cli.run(["build", "robot.yaml"]) == 143
    assert "interrupted" in capsys.readouterr().err
