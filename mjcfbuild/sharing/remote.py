"""A remote product cache on any fsspec URL or shared folder: read-through, write-back.

A product missing from the local store is looked up here before it is computed; a product
computed by this build is uploaded in the background and the build waits for the uploads
before it returns. Objects are verified on download (:mod:`mjcfbuild.sharing.blob`): a bad one
is ignored, the product is rebuilt and uploaded again over it. A remote that cannot be reached
or refuses access is a warning, once, and the build carries on without it.
"""

from __future__ import annotations

import os
import shutil
import threading
import uuid
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path
from typing import Protocol

from mjcfbuild.engine.store import ProductStore
from mjcfbuild.sharing.blob import BadObject, pack, unpack, verify
from mjcfbuild.sharing.settings import RemoteSpec
from mjcfbuild.sharing.stats import ShareStats

LAYOUT = "products-v1"
_SECRET_VARIABLES = ("AWS_SECRET_ACCESS_KEY", "AWS_SESSION_TOKEN", "GOOGLE_APPLICATION_CREDENTIALS")


class Backend(Protocol):
    """The two operations a remote cache needs."""

    def get(self, name: str) -> bytes | None:
        """The object ``name``, or None when there is none."""

    def put(self, name: str, data: bytes) -> None:
        """Store ``data`` as ``name``; a reader sees the old object or the new, never a mix."""


class FolderBackend:
    """A shared folder (a network mount, for example), with plain file calls."""

    def __init__(self, root: Path) -> None:
        self.root = root

    def get(self, name: str) -> bytes | None:
        try:
            return (self.root / name).read_bytes()
        except FileNotFoundError:
            return None

    def put(self, name: str, data: bytes) -> None:
        target = self.root / name
        target.parent.mkdir(parents=True, exist_ok=True)
        temporary = target.with_name(f".{target.name}.{uuid.uuid4().hex}.tmp")
        try:
            temporary.write_bytes(data)
            os.replace(temporary, target)  # atomic: concurrent writers of a key never mix
        finally:
            temporary.unlink(missing_ok=True)


class FsspecBackend:
    """Any fsspec file system: S3 (and MinIO), GCS, HTTP (read-only)."""

    def __init__(self, spec: RemoteSpec, environ: dict[str, str]) -> None:
        import fsspec

        options: dict = {"skip_instance_cache": True}
        if spec.protocol in ("s3", "s3a"):
            # Fail fast when the endpoint is down: one retry, short connect timeout.
            options["config_kwargs"] = {
                "connect_timeout": 5,
                "read_timeout": 60,
                "retries": {"max_attempts": 2, "mode": "standard"},
            }
            endpoint = environ.get("AWS_ENDPOINT_URL_S3") or environ.get("AWS_ENDPOINT_URL")
            if endpoint:
                options["endpoint_url"] = endpoint
        self.fs = fsspec.filesystem(spec.protocol, **options)
        self.root = spec.url.rstrip("/") if spec.read_only else spec.path

    def _path(self, name: str) -> str:
        return f"{self.root}/{name}"

    def get(self, name: str) -> bytes | None:
        try:
            return self.fs.cat_file(self._path(name))
        except FileNotFoundError:
            return None

    def put(self, name: str, data: bytes) -> None:
        self.fs.pipe_file(self._path(name), data)  # one PUT: atomic on S3 and GCS


def open_backend(spec: RemoteSpec, environ: dict[str, str]) -> Backend:
    """The backend of ``spec``: plain files for a folder, fsspec for everything else."""
    if spec.local:
        return FolderBackend(Path(os.path.expanduser(spec.path)))
    return FsspecBackend(spec, environ)


def object_name(key: str) -> str:
    """Where the product ``key`` lives under the remote's prefix."""
    return f"{LAYOUT}/{key[:2]}/{key}"


class RemoteCache:
    """One build's view of a remote cache: fetches, background uploads, warnings, counters."""

    def __init__(
        self,
        spec: RemoteSpec,
        stats: ShareStats,
        warn: Callable[[str], None],
        environ: dict[str, str] | None = None,
        backend: Backend | None = None,
    ) -> None:
        self.spec = spec
        self.stats = stats
        self._warn = warn
        self._environ = dict(os.environ if environ is None else environ)
        self._backend = backend
        self._lock = threading.Lock()
        self._disabled = False
        self._warned_bad = False
        self._uploads: ThreadPoolExecutor | None = None
        self._pending: list[Future] = []

    @property
    def enabled(self) -> bool:
        """False once the remote failed: the rest of the build does without it."""
        return not self._disabled

    def _open(self) -> Backend:
        with self._lock:
            if self._backend is None:
                self._backend = open_backend(self.spec, self._environ)
            return self._backend

    def fetch_into(self, key: str, store: ProductStore) -> bool:
        """Download the product ``key`` into ``store``; whether it was there and intact."""
        if self._disabled:
            return False
        try:
            data = self._open().get(object_name(key))
        except Exception as exc:  # any failure of the remote: warn once, go on without it
            self._failed(exc)
            return False
        if data is None:
            self.stats.count("remote_misses")
            return False
        temporary = store.temporary_folder(key)
        try:
            summary = unpack(key, data, temporary)
            store.store(key, temporary, summary)
        except BadObject as exc:
            self._rejected(key, str(exc))
            return False
        except OSError:
            return False  # the local store cannot be written: compute here
        finally:
            shutil.rmtree(temporary, ignore_errors=True)
        if not store.has(key):
            return False
        self.stats.count("remote_hits")
        return True

    def upload_later(self, key: str, store: ProductStore) -> None:
        """Upload the product ``key`` from ``store`` in the background (see :meth:`wait`)."""
        if self._disabled or self.spec.read_only:
            return
        with self._lock:
            if self._uploads is None:
                self._uploads = ThreadPoolExecutor(4, thread_name_prefix="mjcfbuild-upload")
            self._pending.append(self._uploads.submit(self._upload, key, store))

    def _upload(self, key: str, store: ProductStore) -> None:
        if self._disabled:
            return
        entry = store.read(key)
        if entry is None:
            return  # pruned or unreadable since: nothing to share
        folder, summary = entry
        try:
            data = pack(key, folder, summary)
            verify(key, data)  # the local files still match their summary: share nothing else
        except (OSError, KeyError, BadObject):
            return
        try:
            # No existence check first: this build only computes a product after the remote
            # missed it (or failed), and a racing writer of the same key writes the same bytes.
            self._open().put(object_name(key), data)
        except Exception as exc:
            self._failed(exc)
            return
        self.stats.count("uploaded")

    def wait(self) -> None:
        """Finish every upload this build started."""
        with self._lock:
            pending, self._pending = self._pending, []
            uploads, self._uploads = self._uploads, None
        for future in pending:
            future.result()
        if uploads is not None:
            uploads.shutdown(wait=True)

    def _failed(self, exc: BaseException) -> None:
        with self._lock:
            if self._disabled:
                return
            self._disabled = True
        self.stats.count("remote_errors")
        what = "refused access" if isinstance(exc, PermissionError) else "cannot be used"
        self._warn(
            f"remote cache {self.spec.display} {what} ({self._describe(exc)}); "
            "this build goes on with the local cache only"
        )

    def _rejected(self, key: str, reason: str) -> None:
        self.stats.count("remote_rejected")
        with self._lock:
            first = not self._warned_bad
            self._warned_bad = True
        if first:
            self._warn(
                f"remote cache {self.spec.display}: ignored object {key[:16]}... ({reason}); "
                "the product is rebuilt here and uploaded again"
            )

    def _describe(self, exc: BaseException) -> str:
        """The first line of an error, with anything secret taken out."""
        text = (str(exc).strip().splitlines() or [""])[0][:200] or type(exc).__name__
        for variable in _SECRET_VARIABLES:
            secret = self._environ.get(variable)
            if secret and len(secret) >= 4:
                text = text.replace(secret, "***")
        if self.spec.url != self.spec.display:
            text = text.replace(self.spec.url, self.spec.display)
        return f"{type(exc).__name__}: {text}" if type(exc).__name__ not in text else text
