"""The shared product cache: keys, fetch, store, prune by recent use, sizes."""

from __future__ import annotations

import hashlib
import json
import os
import time

import pytest

from mjcfbuild.products.store import ProductStore, parse_size, product_key


def product(folder, text):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "mesh.obj").write_text(text)
    digest = hashlib.md5(text.encode(), usedforsecurity=False).hexdigest()
    return {"files": {"mesh.obj": digest}, "parts": []}


def test_keys_depend_on_bytes_and_parameters(tmp_path):
    source = tmp_path / "a.stl"
    source.write_bytes(b"one")
    first = product_key("mesh", {"roles": ["visual"]}, [source])
    assert first == product_key("mesh", {"roles": ["visual"]}, [source])
    assert first != product_key("mesh", {"roles": ["collision"]}, [source])
    source.write_bytes(b"two")
    assert first != product_key("mesh", {"roles": ["visual"]}, [source])


def test_store_then_fetch_into_another_folder(tmp_path):
    store = ProductStore(tmp_path / "cache")
    summary = product(tmp_path / "made", "v 0 0 0\n")
    store.store("ab" * 32, tmp_path / "made", summary)
    target = tmp_path / "elsewhere"
    target.mkdir()
    (target / "stale.obj").write_text("old")
    assert store.fetch("ab" * 32, target) == summary
    assert sorted(p.name for p in target.iterdir()) == ["mesh.obj"]
    assert store.fetch("cd" * 32, target) is None


@pytest.mark.parametrize(
    ("kind", "name"),
    [("selfcollision", "matrix.json"), ("reference", "reference.json"), ("preview", "picture.png")],
)
def test_a_one_file_product_is_fetched_as_stored_and_never_when_spoiled(tmp_path, kind, name):
    store = ProductStore(tmp_path / "cache")
    key = "cd" * 32
    assert store.fetch_file(key, name, kind) is None
    assert store.store_file(key, name, b"\x89 the bytes", kind)
    assert store.fetch_file(key, name, kind) == b"\x89 the bytes"
    (store.folder / key[:2] / key / name).write_bytes(b"changed in the cache")
    assert store.fetch_file(key, name, kind) is None
    assert store.dropped == [(key, f"{name} does not match its digest")] and not store.has(key)
    # A file of another name is not that kind's product: never stored.
    assert not store.store_file(key, "other.bin", b"bytes", kind)


def test_prune_removes_least_recently_used_first(tmp_path):
    store = ProductStore(tmp_path / "cache")
    for index, key in enumerate(["aa" * 32, "bb" * 32, "cc" * 32]):
        store.store(key, tmp_path / key[:2], product(tmp_path / key[:2], "x" * 1000))
        summary = store.folder / key[:2] / key / "summary.json"
        os.utime(summary, (time.time() - 100 + index, time.time() - 100 + index))
    store.fetch("aa" * 32, tmp_path / "use")  # now the most recently used
    assert store.prune(max_bytes=2200) == 1
    assert store.fetch("bb" * 32, tmp_path / "x") is None
    assert store.fetch("aa" * 32, tmp_path / "x") is not None
    assert store.usage().entries == 2
    assert store.clear() == 2 and store.usage().entries == 0


def test_a_build_measures_the_cache_only_when_it_may_have_outgrown_its_cap(tmp_path):
    store = ProductStore(tmp_path / "cache", max_bytes=3500)
    keys = ["aa" * 32, "bb" * 32, "cc" * 32, "dd" * 32]
    for key in keys[:2]:
        store.store(key, tmp_path / key[:2], product(tmp_path / key[:2], "x" * 1000))
    assert store.estimated_bytes() is None  # never measured: the first build measures
    assert store.prune_if_full() == 0
    measured = store.estimated_bytes()
    assert measured is not None and measured == store.usage().bytes
    # Each entry stored since adds its size to the estimate, without a measurement.
    store.store(keys[2], tmp_path / "cc", product(tmp_path / "cc", "x" * 1000))
    assert store.estimated_bytes() == store.usage().bytes
    # Under the cap by the estimate: nothing is measured, even where a program outside the
    # store (here, this test) made the cache larger behind its back.
    (store.folder / "bb" / keys[1] / "extra.bin").write_bytes(b"x" * 5000)
    assert store.prune_if_full() == 0 and store.usage().entries == 3
    # Over the cap by the estimate: measured and pruned, least recently used first.
    store.store(keys[3], tmp_path / "dd", product(tmp_path / "dd", "x" * 1000))
    assert store.prune_if_full() >= 1
    assert store.usage().bytes <= 3500 and store.estimated_bytes() == store.usage().bytes


def test_a_measurement_an_hour_old_is_not_trusted(tmp_path):
    store = ProductStore(tmp_path / "cache", max_bytes=1500)
    for key in ["aa" * 32, "bb" * 32]:
        store.store(key, tmp_path / key[:2], product(tmp_path / key[:2], "x" * 1000))
        store.prune()
    usage = store.folder / ".usage.json"
    record = json.loads(usage.read_text())
    assert record["bytes"] <= 1500
    (store.folder / "bb" / ("bb" * 32) / "extra.bin").write_bytes(b"x" * 5000)
    usage.write_text(json.dumps({**record, "measured": time.time() - 3601}))
    assert store.estimated_bytes() is None
    assert store.prune_if_full() == 1 and store.usage().bytes <= 1500


def test_parse_size():
    assert parse_size("512") == 512
    assert parse_size("2K") == 2048
    assert parse_size("1.5G") == int(1.5 * 1024**3)
    assert parse_size("3MiB") == 3 * 1024**2
    with pytest.raises(ValueError):
        parse_size("lots")


def test_an_unusable_product_is_never_stored(tmp_path):
    store = ProductStore(tmp_path / "cache")
    summary = product(tmp_path / "made", "v 0 0 0\n")
    wrong = {**summary, "files": {"mesh.obj": "0" * 32}}
    assert not store.store("ab" * 32, tmp_path / "made", wrong)
    assert not store.store(
        "ab" * 32, tmp_path / "made", {**summary, "parts": ["part000.obj"]}, "decompose"
    )
    assert not store.has("ab" * 32) and store.usage().entries == 0
    assert store.store("ab" * 32, tmp_path / "made", summary)


@pytest.mark.parametrize(
    "spoil",
    ["summary names a missing file", "file changed", "file removed", "summary unreadable"],
)
def test_an_unusable_entry_is_dropped_and_counted(tmp_path, spoil):
    store = ProductStore(tmp_path / "cache")
    key = "ab" * 32
    summary = product(tmp_path / "made", "v 0 0 0\n")
    summary["parts"] = ["mesh.obj"]
    assert store.store(key, tmp_path / "made", summary, "decompose")
    entry = store.folder / key[:2] / key
    if spoil == "summary names a missing file":
        summary["parts"].append("part001.obj")
        (entry / "summary.json").write_text(json.dumps(summary))
    elif spoil == "file changed":
        (entry / "mesh.obj").write_text("v 1 1 1\n")
    elif spoil == "file removed":
        (entry / "mesh.obj").unlink()
    else:
        (entry / "summary.json").write_text("{")

    assert store.fetch(key, tmp_path / "use", "decompose") is None
    assert [k for k, _ in store.dropped] == [key] and not entry.exists()
    assert store.fetch(key, tmp_path / "use", "decompose") is None  # dropped once
    assert len(store.dropped) == 1
