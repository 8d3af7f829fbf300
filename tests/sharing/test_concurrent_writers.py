"""Machines that upload the same product at once: every reader sees one whole object."""

from __future__ import annotations

import hashlib
import threading

import pytest

from mjcfbuild.products.store import ProductStore
from mjcfbuild.sharing.blob import verify
from mjcfbuild.sharing.remote import RemoteCache, object_name
from mjcfbuild.sharing.stats import ShareStats
from mjcfbuild.sharing_settings import parse_remote
from tests.sharing.conftest import s3_objects

KEY = "5e" * 32


def local_store(folder) -> ProductStore:
    """A store holding one product of a few hundred kilobytes under KEY."""
    made = folder / "made"
    made.mkdir(parents=True)
    data = bytes(range(256)) * 2000
    (made / "mesh.obj").write_bytes(data)
    summary = {"files": {"mesh.obj": hashlib.md5(data, usedforsecurity=False).hexdigest()}}
    store = ProductStore(folder / "cache")
    store.store(KEY, made, summary)
    return store


def race(remote_url: str, store: ProductStore, writers: int = 6) -> list[str]:
    """``writers`` builds upload KEY at the same moment; the warnings they gave."""
    warnings: list[str] = []
    caches = [
        RemoteCache(parse_remote(remote_url), ShareStats(), warnings.append) for _ in range(writers)
    ]
    start = threading.Barrier(writers)

    def upload(cache: RemoteCache) -> None:
        start.wait()
        cache.upload_later(KEY, store)
        cache.wait()

    threads = [threading.Thread(target=upload, args=(cache,)) for cache in caches]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return warnings


@pytest.mark.parametrize("where", ["folder", "s3"])
def test_concurrent_writers_of_one_key_leave_one_whole_object(tmp_path, where, request):
    store = local_store(tmp_path)
    if where == "folder":
        remote = str(tmp_path / "shared")
        assert race(remote, store) == []
        files = [p for p in (tmp_path / "shared").rglob("*") if p.is_file()]
        assert [p.name for p in files] == [KEY]  # no temporary files left behind
        data = files[0].read_bytes()
    else:
        remote = request.getfixturevalue("s3_remote")
        assert race(remote, store) == []
        objects = s3_objects(remote)
        assert list(objects) == [f"team/{object_name(KEY)}"]
        data = objects[f"team/{object_name(KEY)}"]
    _, files = verify(KEY, data)
    assert files["mesh.obj"] == (store.read(KEY)[0] / "mesh.obj").read_bytes()
