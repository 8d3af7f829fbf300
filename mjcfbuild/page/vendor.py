"""MuJoCo's WebAssembly build (``@mujoco/mujoco`` on npm), fetched once into the user cache.

The version is pinned and the tarball is checked against the registry's sha512 ``integrity``
before it is used, wherever it came from: the registry (or the mirror
``$MJCFBUILD_NPM_REGISTRY`` names), the cache, or a copy named by ``$MJCFBUILD_MUJOCO_JS`` for
machines without access to a registry.
"""

from __future__ import annotations

import base64
import hashlib
import os
import tarfile
import urllib.error
import urllib.request
from dataclasses import dataclass
from pathlib import Path

from mjcfbuild.cachedir import user_cache_dir
from mjcfbuild.errors import InputError, MjcfbuildError

PACKAGE = "@mujoco/mujoco"
VERSION = "3.14.0"
INTEGRITY = (  # the registry's `dist.integrity` for VERSION
    "sha512-WPUYidu4Fx8+uM4hQv80SOA0ifpWGrsNJguKs8JBV8SCTxjKQ2/rqsh880nUH0/Vwa8vuefghvCQkkoed3bkUg=="
)
REGISTRY = "https://registry.npmjs.org"
REGISTRY_SETTING = "MJCFBUILD_NPM_REGISTRY"  # a mirror of the npm registry
TARBALL = f"mujoco-{VERSION}.tgz"
LOCAL_COPY = "MJCFBUILD_MUJOCO_JS"  # a path to the tarball, for offline machines
TIMEOUT = 60.0  # seconds without an answer before the download is given up


@dataclass(frozen=True)
class MujocoJs:
    """The two files the page needs from the package: the ES module and the WebAssembly."""

    script: bytes
    wasm: bytes


def mujoco_js() -> MujocoJs:
    """The package's single-threaded build, downloaded into the cache on first use."""
    tarball = _tarball()
    try:
        with tarfile.open(tarball, "r:gz") as archive:
            return MujocoJs(
                script=_member(archive, "package/mujoco.js"),
                wasm=_member(archive, "package/mujoco.wasm"),
            )
    except (OSError, tarfile.TarError, KeyError) as exc:
        raise InputError(f"cannot read {PACKAGE} {VERSION} from {tarball}: {exc}") from exc


def _member(archive: tarfile.TarFile, name: str) -> bytes:
    handle = archive.extractfile(name)
    if handle is None:
        raise KeyError(name)
    return handle.read()


def _tarball() -> Path:
    """A verified copy of the tarball: the one ``$MJCFBUILD_MUJOCO_JS`` names, else the
    cache's, else one downloaded now."""
    local = os.environ.get(LOCAL_COPY)
    if local:
        path = Path(local).expanduser()
        try:
            data = path.read_bytes()
        except OSError as exc:
            raise InputError(
                f"{LOCAL_COPY}={local}: cannot read it ({exc.strerror or exc}); "
                f"point it at {TARBALL} (`npm pack {PACKAGE}@{VERSION}`)"
            ) from exc
        _verify(data, f"{LOCAL_COPY}={local}")
        return path
    cached = user_cache_dir() / "npm" / TARBALL
    if cached.is_file() and _matches(cached.read_bytes()):
        return cached
    data = _download()
    _verify(data, f"{_url()} (download)")
    cached.parent.mkdir(parents=True, exist_ok=True)
    temporary = cached.with_name(f".{cached.name}.{os.getpid()}")
    temporary.write_bytes(data)
    os.replace(temporary, cached)
    return cached


def _registry() -> str:
    return (os.environ.get(REGISTRY_SETTING) or REGISTRY).rstrip("/")


def _url() -> str:
    return f"{_registry()}/{PACKAGE}/-/{TARBALL}"


def _download() -> bytes:
    try:
        with urllib.request.urlopen(_url(), timeout=TIMEOUT) as response:
            return bytes(response.read())
    except (urllib.error.URLError, OSError, ValueError) as exc:
        reason = getattr(exc, "reason", None) or exc
        raise MjcfbuildError(
            f"output.page: cannot download {PACKAGE} {VERSION} from {_registry()} ({reason}); "
            f"connect to the registry once (the copy is cached), or set {LOCAL_COPY} to a "
            f"copy of {TARBALL} (`npm pack {PACKAGE}@{VERSION}`), or set output.page: false"
        ) from exc


def _matches(data: bytes) -> bool:
    digest = base64.b64encode(hashlib.sha512(data).digest()).decode()
    return f"sha512-{digest}" == INTEGRITY


def _verify(data: bytes, origin: str) -> None:
    if not _matches(data):
        raise InputError(
            f"{origin}: not {PACKAGE} {VERSION} (its sha512 differs from the registry's "
            f"integrity {INTEGRITY[:20]}...); use the registry's {TARBALL}"
        )
