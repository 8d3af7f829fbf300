"""``@mujoco/mujoco`` from the npm registry: pinned, checked against its integrity, cached, and
the ways around a registry this machine cannot reach (a mirror, a local copy)."""

from __future__ import annotations

import functools
import io
import shutil
import tarfile
import threading
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import pytest

from mjcfbuild.errors import InputError, MjcfbuildError
from mjcfbuild.page import vendor

UNREACHABLE = "http://127.0.0.1:9"  # the discard port: nothing answers


@pytest.fixture(scope="module")
def tarball(tmp_path_factory) -> Path:
    """The pinned tarball, downloaded from the registry once for this module."""
    cache = tmp_path_factory.mktemp("npm-cache")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("MJCFBUILD_CACHE_DIR", str(cache))
        patch.delenv(vendor.LOCAL_COPY, raising=False)
        patch.delenv(vendor.REGISTRY_SETTING, raising=False)
        vendor.mujoco_js()
    return cache / "npm" / vendor.TARBALL


@pytest.fixture
def offline(tmp_path, monkeypatch) -> Path:
    """An empty cache and a registry that does not answer; the cache folder."""
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv(vendor.REGISTRY_SETTING, UNREACHABLE)
    monkeypatch.delenv(vendor.LOCAL_COPY, raising=False)
    return tmp_path / "cache"


def test_the_registry_tarball_has_the_module_and_the_webassembly(tarball):
    assert vendor._matches(tarball.read_bytes())
    with tarfile.open(tarball) as archive:
        names = set(archive.getnames())
    assert {"package/mujoco.js", "package/mujoco.wasm"} <= names


def test_the_cached_copy_is_used_without_the_registry(tarball, offline):
    (offline / "npm").mkdir(parents=True)
    shutil.copy(tarball, offline / "npm" / vendor.TARBALL)
    files = vendor.mujoco_js()
    assert files.wasm[:4] == b"\0asm"
    assert b"export default loadMujoco;" in files.script


def test_a_cached_copy_that_is_not_the_pinned_one_is_not_used(offline):
    (offline / "npm").mkdir(parents=True)
    (offline / "npm" / vendor.TARBALL).write_bytes(b"half a download")
    with pytest.raises(MjcfbuildError) as error:
        vendor.mujoco_js()  # it goes to the registry, which does not answer
    message = str(error.value)
    assert "cannot download @mujoco/mujoco 3.14.0 from http://127.0.0.1:9" in message
    assert vendor.LOCAL_COPY in message and "output.page: false" in message
    assert "\n" not in message


def test_a_mirror_serves_the_tarball(tarball, offline, tmp_path, monkeypatch):
    mirror = tmp_path / "mirror"
    (mirror / "@mujoco" / "mujoco" / "-").mkdir(parents=True)
    shutil.copy(tarball, mirror / "@mujoco" / "mujoco" / "-" / vendor.TARBALL)
    handler = functools.partial(SimpleHTTPRequestHandler, directory=str(mirror))
    handler.log_message = lambda *args: None  # type: ignore[attr-defined]
    server = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        monkeypatch.setenv(vendor.REGISTRY_SETTING, f"http://127.0.0.1:{server.server_port}/")
        assert vendor.mujoco_js().wasm[:4] == b"\0asm"
    finally:
        server.shutdown()
        thread.join()
    assert (offline / "npm" / vendor.TARBALL).read_bytes() == tarball.read_bytes()  # cached


def test_a_local_copy_serves_an_offline_machine(tarball, offline, monkeypatch):
    monkeypatch.setenv(vendor.LOCAL_COPY, str(tarball))
    assert vendor.mujoco_js().wasm[:4] == b"\0asm"
    assert not (offline / "npm").exists()  # read where it is


def test_a_local_copy_of_something_else_is_refused(offline, tmp_path, monkeypatch):
    other = tmp_path / "mujoco-3.14.0.tgz"
    with tarfile.open(other, "w:gz") as archive:
        data = b"export default loadMujoco;"
        member = tarfile.TarInfo("package/mujoco.js")
        member.size = len(data)
        archive.addfile(member, io.BytesIO(data))
    monkeypatch.setenv(vendor.LOCAL_COPY, str(other))
    with pytest.raises(InputError, match=r"MJCFBUILD_MUJOCO_JS=.*: not @mujoco/mujoco 3\.14\.0"):
        vendor.mujoco_js()


def test_a_local_copy_that_is_missing_says_so(offline, tmp_path, monkeypatch):
    monkeypatch.setenv(vendor.LOCAL_COPY, str(tmp_path / "nowhere.tgz"))
    with pytest.raises(InputError, match=r"MJCFBUILD_MUJOCO_JS=.*nowhere\.tgz: cannot read it"):
        vendor.mujoco_js()
