"""When a file's bytes may be taken as unchanged without reading them (git's rule).

A file counts as unchanged only when everything that can reveal a change agrees with what was
recorded: its size, modification time and status-change time to the nanosecond, its inode and
its device. The modification time alone misses a restored time: ``cp -p``, ``rsync -a``,
``tar``, ``unzip`` and ``os.utime`` set it back, and ``git archive`` stamps every file with its
commit's second. The status-change time (ctime) cannot be set: every write, every restore of
the modification time, a rename or a new link moves it to now. The inode and device tell a
file replaced by another at the same path (a folder removed and extracted again).

A signature recorded in the same timestamp tick as the file's last change cannot tell a later
change in that tick (git's "racily clean" files): a file changed less than a margin before its
record is hashed again next time rather than trusted. The margin is the file system's tick:
:data:`RACY_NS` (2 s) where its times are coarse (FAT: 2 s; ext3, HFS+: 1 s; exFAT: 10 ms),
told by a status-change time in whole milliseconds, and :data:`TICK_RACY_NS` (0.1 s) where
they are finer: those file systems take times from the kernel's file clock, which moves once a
tick (at most 10 ms on Linux, 15.6 ms on Windows) and lags ``time.time()`` by up to a tick. So
the files a build wrote are trusted by the next no-op unless they were written in its last
tenth of a second, where a 2 s margin had it hash most of a fast build's outputs again.

Only the standard library is imported: the no-op path uses this before anything else.
"""

from __future__ import annotations

import os
import sys
import time

RACY_NS = 2_000_000_000  # file systems with coarse times
TICK_RACY_NS = 100_000_000  # file systems with sub-millisecond times: a clock tick, with margin
_TICK_NS = 16_000_000  # the longest tick of a kernel's file clock (Windows: 15.6 ms)
_CLOCK_REALTIME_COARSE = 5  # Linux's clock id (not in Python's time module)


def signature(stat: os.stat_result) -> list[int]:
    """What identifies the file of ``stat`` short of its bytes: size, mtime and ctime (ns),
    inode, device. Two equal signatures taken :func:`racy`-free mean the same bytes."""
    return [stat.st_size, stat.st_mtime_ns, stat.st_ctime_ns, stat.st_ino, stat.st_dev]


def racy(stat: os.stat_result, recorded_ns: int) -> bool:
    """Whether a signature of ``stat`` recorded at ``recorded_ns`` (``time.time_ns()``) could
    miss a later change: the file was modified (or its times set) too shortly before. A time in
    the future counts as racy too."""
    # The status-change time is always the file system's clock (it cannot be set), so its
    # resolution is the file system's; one in whole milliseconds is taken as coarse (a fine
    # one lands there once in a million, and is only hashed again).
    fine = stat.st_ctime_ns % 1_000_000 != 0
    margin = min(RACY_NS, TICK_RACY_NS) if fine else RACY_NS
    return recorded_ns - max(stat.st_mtime_ns, stat.st_ctime_ns) < margin


def file_clock_ns() -> int:
    """Now, by the clock the file system stamps status-change times with where that is known
    (Linux: the coarse real-time clock, which lags ``time.time_ns()`` by up to a tick), else
    ``time.time_ns()`` less a tick: a file changed from now on has a status-change time no
    earlier, on a file system whose times are fine."""
    if sys.platform.startswith("linux"):
        return time.clock_gettime_ns(_CLOCK_REALTIME_COARSE)
    return time.time_ns() - _TICK_NS


def changed_since(stat: os.stat_result, since_ns: int) -> bool:
    """Whether the file of ``stat`` may have changed at or after ``since_ns``
    (:func:`file_clock_ns`): its status-change time (which every change moves, and nothing
    can set back) is that late, or within :data:`RACY_NS` of it where times are coarse. The
    modification time says nothing here: ``touch -d`` sets it anywhere."""
    fine = stat.st_ctime_ns % 1_000_000 != 0
    return stat.st_ctime_ns >= (since_ns if fine else since_ns - RACY_NS)
