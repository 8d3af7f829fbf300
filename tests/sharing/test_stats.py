"""Counters of what remotes gave and took, kept in the local cache folder for ``cache show``."""

from __future__ import annotations

import threading

from mjcfbuild.sharing.stats import ShareStats, read, record


def test_builds_add_up_and_the_last_one_is_kept(tmp_path, cli):
    record(tmp_path, "s3://bucket/x", {"remote_hits": 3, "remote_misses": 2, "uploaded": 2})
    record(tmp_path, "s3://bucket/x", {"remote_hits": 5})
    entry = read(tmp_path)["s3://bucket/x"]
    assert entry["total"]["remote_hits"] == 8 and entry["total"]["uploaded"] == 2
    assert entry["last_build"]["remote_hits"] == 5 and entry["last_build"]["uploaded"] == 0
    shown = cli("cache", "show", "--folder", str(tmp_path))
    assert "remote s3://bucket/x: last build 5 hits, 0 misses, 0 uploaded; in all 8 hits" in (
        shown.stdout
    )


def test_counters_are_safe_across_threads():
    stats = ShareStats()
    threads = [
        threading.Thread(target=lambda: [stats.computed("mesh", "here") for _ in range(500)])
        for _ in range(4)
    ]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert stats.as_dict()["computed"] == {"mesh": {"here": 2000, "on_cluster": 0}}
    assert stats.as_dict()["computed_here"] == 2000


def test_an_unreadable_record_is_no_record(tmp_path):
    (tmp_path / "remote-stats.json").write_text("{not json")
    assert read(tmp_path) == {}
    record(tmp_path, "/mnt/share", {"uploaded": 1})
    assert read(tmp_path)["/mnt/share"]["total"]["uploaded"] == 1
