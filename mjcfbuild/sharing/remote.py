"""A remote product cache on any fsspec URL or shared folder: read-through, write-back.

A product missing from the local store is looked up here before it is computed; a product
computed by this build is uploaded in the background and the build waits for the uploads
before it returns. Objects are verified on download (:mod:`mjcfbuild.sharing.blob`) and checked
for use (:mod:`mjcfbuild.products.usable`: every file the summary names is there): a bad one is
ignored, never stored, the product is rebuilt and uploaded again over it; with a signing key
(``MJCFBUILD_CACHE_KEY``) so is an object it did not sign. A remote that cannot be reached,
refuses access or does not answer within ``MJCFBUILD_REMOTE_TIMEOUT`` seconds (each call, and
the wait for the build's last uploads together) is a warning, once, and the build carries on
without it: no remote can hold a build, and the output folder's lock, for longer.
"""

from __future__ import annotations

import os
import queue
import shutil
import threading
import time
import uuid
from collections.abc import Callable
from pathlib import Path
from typing import Protocol, TypeVar

from mjcfbuild.products.store import ProductStore
from mjcfbuild.products.usable import product_problem
from mjcfbuild.sharing.blob import BadObject, pack, unpack, verify
from mjcfbuild.sharing.stats import ShareStats
from mjcfbuild.sharing_settings import RemoteSpec, remote_timeout, signing_key

LAYOUT = "products-v1"
_SECRET_VARIABLES = (
    "AWS_SECRET_ACCESS_KEY",
    "AWS_SESSION_TOKEN",
    "GOOGLE_APPLICATION_CREDENTIALS",
    "MJCFBUILD_CACHE_KEY",
)
_UPLOAD_THREADS = 4
T = TypeVar("T")


class NoAnswer(TimeoutError):
    """The remote did not answer in time."""


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

    def __init__(self, spec: RemoteSpec, environ: dict[str, str], seconds: float = 30.0) -> None:
        import fsspec

        options: dict = {"skip_instance_cache": True}
        if spec.protocol in ("s3", "s3a"):
            # Fail fast when the endpoint is down: one retry, short timeouts (the build gives
            # up on a call after ``seconds`` anyway; these end the thread that made it).
            options["config_kwargs"] = {
                "connect_timeout": min(5.0, seconds),
                "read_timeout": seconds,
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


def open_backend(spec: RemoteSpec, environ: dict[str, str], seconds: float = 30.0) -> Backend:
    """The backend of ``spec``: plain files for a folder, fsspec for everything else."""
    if spec.local:
        return FolderBackend(Path(os.path.expanduser(spec.path)))
    return FsspecBackend(spec, environ, seconds)


def within(seconds: float, call: Callable[[], T]) -> T:
    """``call()``'s result, or :class:`NoAnswer` if it has not returned within ``seconds``.
    The call goes on in a daemon thread, which cannot keep the process from exiting."""
    outcome: list = []
    done = threading.Event()

    def run() -> None:
        try:
            outcome.append((True, call()))
        except BaseException as exc:  # handed to the caller
            outcome.append((False, exc))
        finally:
            done.set()

    threading.Thread(target=run, daemon=True, name="mjcfbuild-remote").start()
    if not done.wait(seconds):
        raise NoAnswer(f"no answer within {seconds:g} s")
    ok, value = outcome[0]
    if not ok:
        raise value
    return value


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
        self._seconds = remote_timeout(self._environ)
        self._secret = signing_key(self._environ)
        # Uploads run in daemon threads: one stuck on a remote that stopped answering must
        # not keep the build's process from exiting once the build gave up waiting.
        self._queue: queue.Queue[tuple[str, ProductStore] | None] = queue.Queue()
        self._threads = 0
        self._unfinished = 0
        self._idle = threading.Condition(self._lock)

    @property
    def enabled(self) -> bool:
        """False once the remote failed: the rest of the build does without it."""
        return not self._disabled

    def _open(self) -> Backend:
        with self._lock:
            if self._backend is None:
                self._backend = open_backend(self.spec, self._environ, self._seconds)
            return self._backend

    def fetch_into(self, key: str, store: ProductStore, kind: str | None = None) -> bool:
        """Download the product ``key`` (of ``kind``) into ``store``; whether it was there,
        intact and usable (see :func:`~mjcfbuild.products.usable.product_problem`)."""
        if self._disabled:
            return False
        try:
            data = within(self._seconds, lambda: self._open().get(object_name(key)))
        except Exception as exc:  # any failure of the remote: warn once, go on without it
            self._failed(exc)
            return False
        if data is None:
            self.stats.count("remote_misses")
            return False
        temporary = store.temporary_folder(key)
        try:
            summary = unpack(key, data, temporary, self._secret)
            problem = product_problem(kind, summary, temporary)
            if problem is not None:
                raise BadObject(f"unusable: {problem}")
            store.store(key, temporary, summary, kind)
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
            self._unfinished += 1
            if self._threads < _UPLOAD_THREADS:
                self._threads += 1
                uploader = threading.Thread(target=self._uploader, daemon=True)
                uploader.start()
        self._queue.put((key, store))

    def _uploader(self) -> None:
        while True:
            item = self._queue.get()
            if item is None:  # the build is done with uploads (see wait)
                return
            key, store = item
            try:
                self._upload(key, store)
            except Exception as exc:  # a bug here must not leave the build waiting
                self._failed(exc)
            finally:
                with self._lock:
                    self._unfinished -= 1
                    self._idle.notify_all()

    def _upload(self, key: str, store: ProductStore) -> None:
        if self._disabled:
            return
        entry = store.read(key)
        if entry is None:
            return  # pruned or unreadable since: nothing to share
        folder, summary = entry
        try:
            data = pack(key, folder, summary, self._secret)
            verify(key, data, self._secret)  # the local files still match their summary
        except (OSError, KeyError, BadObject):
            return
        try:
            # No existence check first: this build only computes a product after the remote
            # missed it (or failed), and a racing writer of the same key writes the same bytes.
            within(self._seconds, lambda: self._open().put(object_name(key), data))
        except Exception as exc:
            self._failed(exc)
            return
        self.stats.count("uploaded")

    def wait(self) -> None:
        """Finish every upload this build started, or give up on those left after
        ``MJCFBUILD_REMOTE_TIMEOUT`` seconds with one warning (the build finishes locally)."""
        deadline = time.monotonic() + self._seconds
        with self._lock:
            while self._unfinished:
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                self._idle.wait(left)
            unfinished = self._unfinished
            if unfinished:
                first = not self._disabled
                self._disabled = True  # uploads still queued are dropped
            threads, self._threads = self._threads, 0
        for _ in range(threads):  # each ends once its upload returned (or was given up)
            self._queue.put(None)
        if unfinished:
            self.stats.count("remote_errors")
            if first:
                plural = "s" if unfinished > 1 else ""
                self._warn(
                    f"remote cache {self.spec.display} did not take {unfinished} upload{plural} "
                    f"within {self._seconds:g} s; this build finished without sharing them"
                )

    def _failed(self, exc: BaseException) -> None:
        with self._lock:
            if self._disabled:
                return
            self._disabled = True
        self.stats.count("remote_errors")
        if isinstance(exc, NoAnswer):
            what = "did not answer in time"
        elif isinstance(exc, PermissionError):
            what = "refused access"
        else:
            what = "cannot be used"
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
