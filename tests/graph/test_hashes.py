"""The hash cache reads a file again unless its whole signature (size, mtime, ctime, inode,
device) is the one its hash was recorded with, and never remembers a racy file."""

from __future__ import annotations

import json
import os
import time

import pytest

from mjcfbuild import filesig
from mjcfbuild.fsutil import md5_file
from mjcfbuild.graph import hashes as hashes_module
from mjcfbuild.graph.hashes import HashCache
from tests.conftest import file_clock_past


@pytest.fixture
def settled(monkeypatch):
    """No racy margin: a hash is remembered as if recorded long after the file's last change
    (a test then waits for the file clock before changing it again)."""
    monkeypatch.setattr(filesig, "RACY_NS", 0)


def test_cached_hash_survives_save_and_reload(tmp_path, monkeypatch, settled):
    data = tmp_path / "a.bin"
    data.write_bytes(b"abc")
    cache = HashCache(tmp_path / "hashes.json")
    digest = cache.md5(data)
    cache.save()
    reads = []
    monkeypatch.setattr(hashes_module, "md5_file", lambda p: reads.append(p) or "x")
    assert HashCache(tmp_path / "hashes.json").md5(data) == digest
    assert reads == []


def test_changed_file_is_read_again(tmp_path):
    data = tmp_path / "a.bin"
    data.write_bytes(b"abc")
    cache = HashCache(None)
    first = cache.md5(data)
    data.write_bytes(b"abcd")
    assert cache.md5(data) != first


def _write_old(path, data: bytes) -> os.stat_result:
    """``path`` with ``data``, modified an hour ago (a checkout, an unpacked archive); its stat."""
    path.write_bytes(data)
    old = time.time_ns() - 3600 * 1_000_000_000
    os.utime(path, ns=(old, old))
    return os.stat(path)


def test_a_same_size_edit_with_its_mtime_restored_is_read_again(tmp_path, settled):
    data = tmp_path / "limits.yaml"
    before = _write_old(data, b"upper: 1.5\n")
    cache = HashCache(tmp_path / "hashes.json")
    first = cache.md5(data)
    cache.save()
    file_clock_past(tmp_path, before.st_ctime_ns)
    data.write_bytes(b"upper: 2.5\n")
    os.utime(data, ns=(before.st_atime_ns, before.st_mtime_ns))
    assert (os.stat(data).st_size, os.stat(data).st_ino) == (before.st_size, before.st_ino)
    assert cache.md5(data) == md5_file(data) != first
    assert HashCache(tmp_path / "hashes.json").md5(data) == md5_file(data)  # reloaded too


def test_a_file_replaced_by_a_copy_with_its_times_is_read_again(tmp_path, settled):
    data, other = tmp_path / "a.stl", tmp_path / "b.stl"
    before = _write_old(data, b"solid a")
    other.write_bytes(b"solid b")
    cache = HashCache(None)
    first = cache.md5(data)
    file_clock_past(tmp_path, before.st_ctime_ns)
    os.utime(other, ns=(before.st_atime_ns, before.st_mtime_ns))
    os.replace(other, data)  # another inode, as tar and unzip leave it
    assert cache.md5(data) == md5_file(data) != first


def test_recently_modified_files_are_not_remembered(tmp_path):
    data = tmp_path / "a.bin"
    data.write_bytes(b"abc")
    cache = HashCache(tmp_path / "hashes.json")
    cache.md5(data)
    cache.save()
    assert not (tmp_path / "hashes.json").exists()


def test_a_file_whose_old_mtime_was_just_restored_is_not_remembered(tmp_path):
    """``cp -p``, ``tar`` and ``git archive`` give a file just written an old mtime: its
    ctime says it changed now, so its hash is not trusted next time."""
    data = tmp_path / "a.bin"
    _write_old(data, b"abc")
    cache = HashCache(tmp_path / "hashes.json")
    cache.md5(data)
    cache.save()
    assert not (tmp_path / "hashes.json").exists()


def test_an_entry_without_ctime_and_device_is_not_trusted(tmp_path):
    data = tmp_path / "a.bin"
    data.write_bytes(b"abc")
    stat = os.stat(data)
    older_format = [stat.st_size, stat.st_mtime_ns, stat.st_ino, "0" * 32]  # before ctime
    (tmp_path / "hashes.json").write_text(json.dumps({str(data): older_format}))
    assert HashCache(tmp_path / "hashes.json").md5(data) == md5_file(data)
