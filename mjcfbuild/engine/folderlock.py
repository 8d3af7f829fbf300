"""The output folder's lock: one build of a folder at a time, and a waiting build knows whom
it waits for.

The lock is an exclusive ``flock`` on ``.mjcfbuild/lock``; the build that holds it writes
itself into the file (:class:`Holder`: its PID, host, start time and what tells a reused PID
apart). A build that finds the lock taken says who holds it, polls, and gives up after its
time limit. The kernel frees the lock of a process that ended; if the lock is still held
although its holder is gone (a process it made that never exec'd kept the file open), the
waiter takes the lock over by removing the file, under a short lock on the folder so that two
waiters never both do. A holder on another machine, in another PID namespace or of an earlier
boot cannot be looked at: it is waited for, never taken over from.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import socket
import time
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import BinaryIO

POLL_SECONDS = 0.1
RUNNING, STOPPED, GONE, UNKNOWN = "running", "stopped", "gone", "unknown"


@dataclass(frozen=True)
class Holder:
    """The build that holds a folder's lock."""

    pid: int
    host: str
    started: float  # when it took the lock (seconds since the epoch)
    process_start: str  # the process's start in clock ticks since boot ("" where unknown)
    boot: str  # the boot's id: a PID from an earlier boot says nothing
    pid_space: str  # the PID namespace: a PID from another one says nothing

    def describe(self) -> str:
        """'pid 1234 on host, since 2026-11-27 05:20:01 UTC', with ', stopped' or ', gone'."""
        since = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime(self.started))
        text = f"pid {self.pid} on {self.host}, since {since}"
        state = self.state()
        return f"{text}, {state}" if state in (STOPPED, GONE) else text

    def state(self) -> str:
        """RUNNING, STOPPED (by a signal: it may go on), GONE, or UNKNOWN (another machine,
        PID namespace or boot: nothing here tells)."""
        here = this_process(0.0)
        if (self.host, self.boot, self.pid_space) != (here.host, here.boot, here.pid_space):
            return UNKNOWN
        try:
            os.kill(self.pid, 0)
        except ProcessLookupError:
            return GONE
        except PermissionError:
            pass  # another user's process: it exists
        status = _process_status(self.pid)
        if status is None:
            return RUNNING  # no /proc: it exists, that is all that can be told
        letter, start = status
        if (self.process_start and start != self.process_start) or letter in "ZX":
            return GONE  # the PID is another process's now, or a zombie's (its files closed)
        return STOPPED if letter in "Tt" else RUNNING


class LockBusy(Exception):
    """The lock was not free within the time limit."""

    def __init__(self, holder: Holder | None, seconds: float) -> None:
        super().__init__("the lock is held")
        self.holder = holder
        self.seconds = seconds


def this_process(started: float | None = None) -> Holder:
    """This process as a lock's holder (``started``: now, unless given)."""
    pid = os.getpid()
    status = _process_status(pid)
    return Holder(
        pid=pid,
        host=socket.gethostname(),
        started=time.time() if started is None else started,
        process_start=status[1] if status else "",
        boot=_read("/proc/sys/kernel/random/boot_id"),
        pid_space=_link("/proc/self/ns/pid"),
    )


def read_holder(path: Path) -> Holder | None:
    """The holder written in the lock file ``path``; None when there is none (free, just
    taken, or taken by a build of an earlier version)."""
    try:
        data = json.loads(path.read_text())
        return Holder(
            pid=int(data["pid"]),
            host=str(data["host"]),
            started=float(data["started"]),
            process_start=str(data["process_start"]),
            boot=str(data["boot"]),
            pid_space=str(data["pid_space"]),
        )
    except (OSError, ValueError, KeyError, TypeError):
        return None


@contextlib.contextmanager
def folder_lock(
    path: Path, seconds: float, on_wait: Callable[[Holder | None], None]
) -> Iterator[None]:
    """Hold the lock file ``path`` (its folder is made if need be). While another build holds it,
    ``on_wait`` is told who (once, and again when that changes); after ``seconds`` of waiting,
    :class:`LockBusy` names the holder. Raises OSError when the file cannot be written."""
    deadline = time.monotonic() + seconds
    told: object = _NOBODY_YET
    while True:
        try:
            handle, holder = _try(path)
        except FileNotFoundError:  # `clean` removed the folder this moment: make it again
            if time.monotonic() >= deadline:
                raise
            continue
        if handle is not None:
            break
        if holder != told:
            on_wait(holder)
            told = holder
        if time.monotonic() >= deadline:
            raise LockBusy(holder, seconds)
        time.sleep(POLL_SECONDS)
    with handle:
        try:
            yield
        finally:
            # A waiter that reads the file between these two calls finds no holder: free.
            with contextlib.suppress(OSError):
                handle.truncate(0)
            fcntl.flock(handle, fcntl.LOCK_UN)


_NOBODY_YET = object()


def _try(path: Path) -> tuple[BinaryIO | None, Holder | None]:
    """One attempt: the lock file, locked and naming this process; else who holds it.

    Taking the lock, writing the holder and taking over from a holder that is gone all happen
    under a short lock on the folder, so the holder a waiter reads there is the one whose lock
    it found taken, and two waiters never both take over."""
    path.parent.mkdir(parents=True, exist_ok=True)  # `clean` may have removed it meanwhile
    guard = os.open(path.parent, os.O_RDONLY | os.O_CLOEXEC)
    try:
        try:
            fcntl.flock(guard, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:  # another build is taking the lock this moment
            return None, read_holder(path)
        while True:
            handle = _lock_file(path)
            if handle is not None:
                handle.write(json.dumps(asdict(this_process())).encode() + b"\n")
                handle.flush()
                return handle, None
            holder = read_holder(path)
            if holder is None or holder.state() != GONE:
                return None, holder
            # Still locked by a process its holder made (which never exec'd): the lock is
            # the file's, so a new file is a free lock.
            path.unlink(missing_ok=True)
    finally:
        os.close(guard)  # and with it the folder's lock


def _lock_file(path: Path) -> BinaryIO | None:
    """The lock file, opened, locked and emptied; None while another holds it."""
    descriptor = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
    handle = os.fdopen(descriptor, "r+b")
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        handle.close()
        return None
    if not _still_there(handle, path):
        # Opened just before its holder removed it (`clean`, a take-over): a lock on a
        # removed file locks nothing.
        handle.close()
        raise FileNotFoundError(path)
    handle.truncate(0)
    return handle


def _still_there(handle: BinaryIO, path: Path) -> bool:
    """Whether ``path`` is still the file ``handle`` has open."""
    try:
        named = os.stat(path)
    except FileNotFoundError:
        return False
    opened = os.fstat(handle.fileno())
    return (named.st_dev, named.st_ino) == (opened.st_dev, opened.st_ino)


def _process_status(pid: int) -> tuple[str, str] | None:
    """A process's state letter and start time (clock ticks since boot), from /proc."""
    text = _read(f"/proc/{pid}/stat")
    # "pid (command) state ... starttime": the command may hold spaces and parentheses.
    fields = text[text.rfind(")") + 2 :].split()
    if len(fields) < 20:
        return None
    return fields[0], fields[19]


def _read(path: str) -> str:
    try:
        with open(path) as handle:
            return handle.read().strip()
    except OSError:
        return ""


def _link(path: str) -> str:
    try:
        return os.readlink(path)
    except OSError:
        return ""
