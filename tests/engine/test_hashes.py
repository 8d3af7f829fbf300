"""The hash cache reads a file again only when its size, mtime or inode changed."""

from __future__ import annotations

import os

from mjcfbuild.engine import hashes as hashes_module
from mjcfbuild.engine.hashes import HashCache


def test_cached_hash_survives_save_and_reload(tmp_path, monkeypatch):
    data = tmp_path / "a.bin"
    data.write_bytes(b"abc")
    old = os.stat(data).st_mtime - 10
    os.utime(data, (old, old))
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


def test_recently_modified_files_are_not_remembered(tmp_path):
    data = tmp_path / "a.bin"
    data.write_bytes(b"abc")
    cache = HashCache(tmp_path / "hashes.json")
    cache.md5(data)
    cache.save()
    assert not (tmp_path / "hashes.json").exists()
