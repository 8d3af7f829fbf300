"""A file's signature changes with anything that can reveal a change of its bytes, and a
signature recorded too soon after a change is racy (git's rule for its index)."""

from __future__ import annotations

import os
import shutil
import time

from mjcfbuild import filesig
from tests.conftest import file_clock_past

HOUR_NS = 3600 * 1_000_000_000


def _write_old(path, data: bytes) -> os.stat_result:
    """``path`` with ``data``, modified an hour ago; its stat."""
    path.write_bytes(data)
    old = time.time_ns() - HOUR_NS
    os.utime(path, ns=(old, old))
    return os.stat(path)


def test_a_same_size_edit_with_its_time_restored_changes_the_signature(tmp_path):
    source = tmp_path / "joint.xacro"
    before = _write_old(source, b'<limit upper="1.5"/>')
    file_clock_past(tmp_path, before.st_ctime_ns)
    source.write_bytes(b'<limit upper="2.5"/>')  # in place: the same inode
    os.utime(source, ns=(before.st_atime_ns, before.st_mtime_ns))
    after = os.stat(source)
    assert (after.st_size, after.st_mtime_ns, after.st_ino) == (
        before.st_size,
        before.st_mtime_ns,
        before.st_ino,
    )  # what a check of size, mtime and inode sees: nothing
    assert filesig.signature(after) != filesig.signature(before)


def test_a_copy_over_the_file_that_keeps_size_and_time_changes_the_signature(tmp_path):
    source, other = tmp_path / "a.stl", tmp_path / "b.stl"
    before = _write_old(source, b"solid a")
    _write_old(other, b"solid b")
    os.utime(other, ns=(before.st_atime_ns, before.st_mtime_ns))
    file_clock_past(tmp_path, before.st_ctime_ns)
    shutil.copy2(other, source)  # cp -p: bytes and times
    after = os.stat(source)
    assert (after.st_size, after.st_mtime_ns) == (before.st_size, before.st_mtime_ns)
    assert filesig.signature(after) != filesig.signature(before)


def test_an_untouched_file_keeps_its_signature_and_reading_it_keeps_it_too(tmp_path):
    source = tmp_path / "robot.yaml"
    before = _write_old(source, b"name: arm\n")
    file_clock_past(tmp_path, before.st_ctime_ns)
    assert source.read_bytes() == b"name: arm\n"
    assert filesig.signature(os.stat(source)) == filesig.signature(before)


def test_a_file_changed_just_before_its_record_is_racy(tmp_path):
    source = tmp_path / "mesh.obj"
    source.write_bytes(b"v 0 0 0\n")
    now = os.stat(source)
    assert filesig.racy(now, time.time_ns())  # written this moment
    assert not filesig.racy(now, now.st_ctime_ns + filesig.RACY_NS)  # recorded well after
    # A restored (old) modification time does not make a just-changed file safe: its
    # status-change time is now.
    old = time.time_ns() - HOUR_NS
    os.utime(source, ns=(old, old))
    assert filesig.racy(os.stat(source), time.time_ns())


def test_a_time_in_the_future_is_racy(tmp_path):
    source = tmp_path / "mesh.obj"
    source.write_bytes(b"v 0 0 0\n")
    later = time.time_ns() + HOUR_NS
    os.utime(source, ns=(later, later))
    assert filesig.racy(os.stat(source), time.time_ns() + filesig.RACY_NS)


def _stat(changed_ns: int) -> os.stat_result:
    """A file's status whose modification and status-change times are ``changed_ns``."""
    times = {"st_atime_ns": changed_ns, "st_mtime_ns": changed_ns, "st_ctime_ns": changed_ns}
    return os.stat_result((0o100644, 1, 2, 1, 0, 0, 5, 0, 0, 0), times)


def test_the_margin_is_a_tick_where_times_are_fine_and_two_seconds_where_coarse():
    # A build's outputs written a fraction of a second before its stamp are trusted by the
    # next no-op where the file system keeps fine times (the kernel's clock moves by ticks of
    # at most 10 ms there), not hashed again.
    fine = 1_700_000_000_123_456_789
    assert not filesig.racy(_stat(fine), fine + filesig.TICK_RACY_NS)
    assert filesig.racy(_stat(fine), fine + filesig.TICK_RACY_NS - 1)
    # Whole seconds (ext3, HFS+) or 2 s (FAT): a change a second later can keep the time.
    coarse = 1_700_000_000_000_000_000
    assert filesig.racy(_stat(coarse), coarse + filesig.TICK_RACY_NS)
    assert filesig.racy(_stat(coarse), coarse + filesig.RACY_NS - 1)
    assert not filesig.racy(_stat(coarse), coarse + filesig.RACY_NS)


def test_a_file_changed_after_the_file_clock_was_read_counts_as_changed_since(tmp_path):
    """Checked against the file system itself: every write, rename and time change made after
    ``file_clock_ns`` gives the file a status-change time the stamp counts as a change (its
    clock is the one the kernel stamps files with, which lags ``time.time_ns()``)."""
    path = tmp_path / "robot.urdf"
    path.write_text("<robot/>")
    for turn in range(300):
        since = filesig.file_clock_ns()
        if turn % 3 == 0:
            path.write_text(f"<robot name='r{turn}'/>")
        elif turn % 3 == 1:
            os.utime(path, ns=(0, 0))  # a time set back: the status-change time still moves
        else:
            (tmp_path / "new").write_text("<robot/>")
            os.replace(tmp_path / "new", path)
        assert filesig.changed_since(os.stat(path), since), turn
