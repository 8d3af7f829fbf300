"""The output folder's lock knows its holder: a waiting build names it, gives up after
``--timeout`` while it is stopped, goes on once it was killed, and takes the lock over when
the holder is gone but a process it forked still holds the file. Real builds, real signals."""

from __future__ import annotations

import fcntl
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from mjcfbuild.engine.folderlock import GONE, RUNNING, STOPPED, UNKNOWN, read_holder
from tests.conftest import ROOT, run_cli

EXIT_OUTPUT = 7


@pytest.fixture
def holding(arm):
    """A real build of the arm that holds its output folder's lock, for as long as the test
    wants: its manifest reads the robot description from stdin, which it does under the lock
    and which the test never closes. Yields the process, once the lock names it."""
    manifest = (arm / "robot.yaml").read_text()
    start, end = manifest.index("source:"), manifest.index("packages:")
    (arm / "stdin.yaml").write_text(
        f'{manifest[:start]}source: {{description: "-"}}\n{manifest[end:]}'
    )
    process = subprocess.Popen(
        [sys.executable, "-m", "mjcfbuild", "build", "stdin.yaml"],
        cwd=arm,
        stdin=subprocess.PIPE,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    lock = arm / "mjcf" / ".mjcfbuild" / "lock"
    while (holder := read_holder(lock)) is None or holder.pid != process.pid:
        assert process.poll() is None, "the holding build ended"
        os.sched_yield()
    yield process
    if process.poll() is None:
        os.kill(process.pid, signal.SIGCONT)
        process.kill()
        process.wait()


def stop(process: subprocess.Popen) -> None:
    """SIGSTOP ``process`` and wait until it has stopped."""
    os.kill(process.pid, signal.SIGSTOP)
    os.waitpid(process.pid, os.WUNTRACED)


def test_a_stopped_holder_is_named_and_given_up_on_after_the_timeout(arm, holding):
    lock = arm / "mjcf" / ".mjcfbuild" / "lock"
    stop(holding)
    assert read_holder(lock).state() == STOPPED

    result = run_cli("build", "--no-check", "--timeout", "1", cwd=arm)  # before: waited forever
    assert result.code == EXIT_OUTPUT, result.stderr
    waiting = result.stdout.splitlines()[0]
    assert waiting.startswith("mjcfbuild: waiting for another build of mjcf (held by pid")
    assert f"pid {holding.pid} on " in waiting and waiting.endswith(", stopped)")
    error = result.stderr.strip()
    assert len(error.splitlines()) == 1 and "Traceback" not in error
    assert error.startswith("mjcfbuild: error: mjcf: another build (pid ")
    assert "still holds the output folder's lock after 1 s" in error
    assert f"kill -CONT {holding.pid}" in error
    assert not (arm / "mjcf" / "example_arm.xml").exists()
    assert read_holder(lock).pid == holding.pid  # a stopped build is not gone: left alone


def test_a_killed_holder_frees_the_folder(arm, holding):
    stop(holding)
    os.kill(holding.pid, signal.SIGKILL)
    holding.wait()
    result = run_cli("build", "--no-check", "--timeout", "60", cwd=arm)
    assert result.code == 0, result.stderr
    assert (arm / "mjcf" / "example_arm.xml").exists()
    # Free after the build: nobody is named.
    assert read_holder(arm / "mjcf" / ".mjcfbuild" / "lock") is None


HOLD_AND_FORK = """
import os, signal, sys, time
from pathlib import Path
from mjcfbuild.engine.folderlock import folder_lock

with folder_lock(Path(sys.argv[1]), 1.0, lambda holder: None):
    child = os.fork()
    if child == 0:  # keeps the lock's open file, as a forked helper that outlives a build
        quiet = os.open(os.devnull, os.O_RDWR)
        for stream in (0, 1, 2):  # not the test's pipes: it reads them to their end
            os.dup2(quiet, stream)
        time.sleep(600)
        os._exit(0)
    print(child, flush=True)
    os.kill(os.getpid(), signal.SIGKILL)
"""


def test_a_lock_kept_by_a_forked_process_of_a_gone_holder_is_taken_over(arm):
    lock = arm / "mjcf" / ".mjcfbuild" / "lock"
    lock.parent.mkdir(parents=True)
    holder = subprocess.run(
        [sys.executable, "-c", HOLD_AND_FORK, str(lock)],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert holder.returncode == -signal.SIGKILL, holder.stderr
    orphan = int(holder.stdout)
    try:
        # The lock is still held, by the orphan.
        with open(lock, "rb") as probe, pytest.raises(BlockingIOError):
            fcntl.flock(probe, fcntl.LOCK_EX | fcntl.LOCK_NB)
        assert read_holder(lock).state() == GONE

        result = run_cli("build", "--no-check", "--timeout", "60", cwd=arm)
        assert result.code == 0, result.stderr
        assert (arm / "mjcf" / "example_arm.xml").exists()
        os.kill(orphan, 0)  # taken over, not by ending anyone
    finally:
        os.kill(orphan, signal.SIGKILL)


def test_a_holder_on_another_machine_is_waited_for_never_taken_over(arm):
    lock = arm / "mjcf" / ".mjcfbuild" / "lock"
    lock.parent.mkdir(parents=True)
    record = {
        "pid": 999999,  # no such process here, which says nothing about the other machine
        "host": "build-server-7",
        "started": 1.8e9,
        "process_start": "1",
        "boot": "another-boot",
        "pid_space": "pid:[1]",
    }
    with open(lock, "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX)  # a network folder's lock, as the other machine holds it
        held.write(json.dumps(record))
        held.flush()
        assert read_holder(lock).state() == UNKNOWN
        result = run_cli("build", "--no-check", "--timeout", "0.5", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    assert "(pid 999999 on build-server-7, since 2027-01-15 08:00:00 UTC)" in result.stderr
    assert "let it finish on build-server-7" in result.stderr
    assert json.loads(lock.read_text()) == record


def test_this_process_is_running(tmp_path):
    from mjcfbuild.engine.folderlock import folder_lock

    lock = tmp_path / "lock"
    with folder_lock(lock, 0.0, lambda holder: None):
        holder = read_holder(lock)
        assert holder is not None and holder.pid == os.getpid() and holder.state() == RUNNING
        told = []
        with pytest.raises(Exception) as busy, folder_lock(lock, 0.0, told.append):
            pass
        assert type(busy.value).__name__ == "LockBusy" and busy.value.holder == holder
        assert told == [holder]
    assert read_holder(lock) is None
    assert Path(lock).exists()


def test_a_folder_removed_while_waiting_is_made_again(tmp_path):
    from mjcfbuild.engine.folderlock import folder_lock

    lock = tmp_path / "mjcf" / ".mjcfbuild" / "lock"  # as `clean` leaves it: no state folder
    with folder_lock(lock, 0.0, lambda holder: None):
        assert read_holder(lock).pid == os.getpid()


def test_a_lock_file_removed_after_it_was_opened_is_not_taken_for_the_lock(tmp_path):
    """A waiter that opened the lock file just before its holder (`clean`) removed it would
    lock a file nobody else can see: it finds out, and makes the file again instead."""
    from mjcfbuild.engine.folderlock import _still_there

    lock = tmp_path / "lock"
    lock.write_bytes(b"")
    with open(lock, "r+b") as opened:
        assert _still_there(opened, lock)
        lock.unlink()
        assert not _still_there(opened, lock)
        lock.write_bytes(b"")  # made again by the next build: another file
        assert not _still_there(opened, lock)
