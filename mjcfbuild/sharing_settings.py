"""Where a build shares products and sends work: parsing and checking the two addresses.

``cache.remote`` (or ``$MJCFBUILD_CACHE_REMOTE``) is an fsspec URL or a shared folder;
``executor`` (or ``--executor``/``$MJCFBUILD_EXECUTOR``) is ``local`` or ``dask://host:port``.
Both are checked here with the standard library only, so a malformed address is a one-line
error even on a build that has nothing to do, and such a build imports nothing heavy.
This module is not in the sharing package: robot.yaml's validation uses it, and the manifest sits
below the sharing package (docs/architecture.md, "Layers").
"""

from __future__ import annotations

import importlib.util
import re
from dataclasses import dataclass
from urllib.parse import urlsplit

REMOTE_VARIABLE = "MJCFBUILD_CACHE_REMOTE"
KEY_VARIABLE = "MJCFBUILD_CACHE_KEY"
KEY_FILE_VARIABLE = "MJCFBUILD_CACHE_KEY_FILE"
TIMEOUT_VARIABLE = "MJCFBUILD_REMOTE_TIMEOUT"
DEFAULT_TIMEOUT = 30.0
_SHORTEST_KEY = 16
EXECUTOR_VARIABLE = "MJCFBUILD_EXECUTOR"
DEFAULT_DASK_PORT = 8786

# protocol -> (module that implements it, the mjcfbuild extra that installs it)
_PROTOCOLS: dict[str, tuple[str | None, str | None]] = {
    "file": (None, None),
    "s3": ("s3fs", "s3"),
    "s3a": ("s3fs", "s3"),
    "gs": ("gcsfs", "gcs"),
    "gcs": ("gcsfs", "gcs"),
    "http": ("aiohttp", "http"),
    "https": ("aiohttp", "http"),
}
_READ_ONLY = {"http", "https"}
_HOST = re.compile(r"^[A-Za-z0-9]([A-Za-z0-9.-]*[A-Za-z0-9])?$|^\[[0-9A-Fa-f:.]+\]$")
_BUCKET = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{1,254}$")


class AddressError(ValueError):
    """An address that cannot be used; the message says why and what to do."""


@dataclass(frozen=True)
class RemoteSpec:
    """A checked remote cache address."""

    url: str
    protocol: str
    path: str

    @property
    def read_only(self) -> bool:
        """HTTP remotes are served by someone else: read, never written."""
        return self.protocol in _READ_ONLY

    @property
    def local(self) -> bool:
        """A shared folder (a mounted network drive, for example), written with plain file calls."""
        return self.protocol == "file"

    @property
    def display(self) -> str:
        """The address as messages and reports show it: without user, password or query."""
        return redact(self.url)


@dataclass(frozen=True)
class ExecutorSpec:
    """A checked executor: ``local`` or the address of a Dask scheduler."""

    kind: str
    address: str = ""

    @property
    def scheduler(self) -> str:
        """The address Dask's client connects to."""
        return f"tcp://{self.address}"


def redact(url: str) -> str:
    """``url`` without credentials, query or fragment (they may hold secrets); otherwise as
    written, so messages show what the user typed."""
    parts = urlsplit(url)
    if "@" not in parts.netloc and not parts.query and not parts.fragment:
        return url
    host = parts.netloc.rpartition("@")[2]
    return f"{parts.scheme}://{host}{parts.path}"


def parse_remote(text: str) -> RemoteSpec:
    """Check a remote cache address: ``s3://bucket/prefix``, ``gs://...``, ``https://...``,
    ``file:///folder`` or an absolute folder path."""
    text = text.strip()
    if not text:
        raise AddressError("the remote cache address is empty")
    if text.startswith("/") or text.startswith("~"):
        return RemoteSpec(text, "file", text)
    if "://" not in text:
        raise AddressError(
            f"'{redact(text)}' is not a URL; use s3://bucket/prefix, gs://bucket/prefix, "
            "https://host/prefix or an absolute folder path"
        )
    parts = urlsplit(text)
    protocol = parts.scheme.lower()
    if protocol not in _PROTOCOLS:
        known = ", ".join(sorted(p for p in _PROTOCOLS if p != "s3a"))
        raise AddressError(
            f"'{protocol}://' is not a protocol mjcfbuild can use for a remote cache "
            f"(known: {known})"
        )
    if protocol == "file":
        if parts.netloc not in ("", "localhost") or not parts.path.startswith("/"):
            raise AddressError(f"'{text}' is not a file URL; use file:///absolute/folder")
        return RemoteSpec(text, "file", parts.path)
    host = parts.hostname or ""
    if protocol in _READ_ONLY:
        if not host or not _HOST.match(host):
            raise AddressError(f"'{redact(text)}' has no valid host name")
        try:
            parts.port  # noqa: B018 - raises ValueError for a port that is not a number
        except ValueError:
            raise AddressError(f"'{redact(text)}' has a port that is not a number") from None
    elif not _BUCKET.match(parts.netloc):
        raise AddressError(
            f"'{redact(text)}' has no valid bucket name; use {protocol}://bucket/prefix"
        )
    return RemoteSpec(text, protocol, f"{parts.netloc}{parts.path}".rstrip("/"))


def missing_package(spec: RemoteSpec) -> str | None:
    """The pip command that installs what ``spec``'s protocol needs, if it is missing."""
    module, extra = _PROTOCOLS[spec.protocol]
    modules = ["fsspec", module] if module else []
    if spec.local:
        modules = []
    for name in modules:
        if importlib.util.find_spec(name) is None:
            return f"pip install 'mjcfbuild[{extra}]'"
    return None


def parse_executor(text: str) -> ExecutorSpec:
    """Check an executor: ``local`` or ``dask://host:port`` (port 8786 if left out)."""
    text = text.strip()
    if text == "local":
        return ExecutorSpec("local")
    if not text.startswith("dask://"):
        raise AddressError(f"'{redact(text)}' is not an executor; use 'local' or dask://host:port")
    parts = urlsplit(text)
    host = parts.hostname or ""
    if not host or not _HOST.match(host) or parts.path not in ("", "/") or parts.query:
        raise AddressError(
            f"'{redact(text)}' is not a Dask scheduler address; use dask://host:port"
        )
    try:
        port = parts.port or DEFAULT_DASK_PORT
    except ValueError:
        raise AddressError(f"'{redact(text)}' has a port that is not a number") from None
    host = f"[{host}]" if ":" in host else host
    return ExecutorSpec("dask", f"{host}:{port}")


def signing_key(environ: dict[str, str]) -> bytes | None:
    """The secret remote products are signed and checked with: ``$MJCFBUILD_CACHE_KEY``, else
    the contents of the file ``$MJCFBUILD_CACHE_KEY_FILE`` (surrounding whitespace removed);
    None when neither is set. Raises :class:`AddressError` for a file that cannot be read or
    a key shorter than 16 characters (too easy to guess)."""
    text = environ.get(KEY_VARIABLE, "").strip()
    origin = f"${KEY_VARIABLE}"
    if not text and environ.get(KEY_FILE_VARIABLE, "").strip():
        name = environ[KEY_FILE_VARIABLE].strip()
        origin = f"${KEY_FILE_VARIABLE} ({name})"
        try:
            with open(name, "rb") as handle:
                text = handle.read(1 << 16).decode("utf-8", "surrogateescape").strip()
        except OSError as exc:
            raise AddressError(f"the signing key file cannot be read ({exc.strerror})") from None
    if not text:
        return None
    if len(text) < _SHORTEST_KEY:
        raise AddressError(
            f"{origin}: the signing key is shorter than {_SHORTEST_KEY} characters; "
            "use a random one, e.g. from `openssl rand -hex 32`"
        )
    return text.encode("utf-8", "surrogateescape")


def remote_timeout(environ: dict[str, str]) -> float:
    """Seconds each call to the remote cache, and the wait for a build's last uploads, may
    take (``$MJCFBUILD_REMOTE_TIMEOUT``, default 30); raises :class:`AddressError` for a value
    that is not a positive number."""
    text = environ.get(TIMEOUT_VARIABLE, "").strip()
    if not text:
        return DEFAULT_TIMEOUT
    try:
        seconds = float(text)
    except ValueError:
        seconds = -1.0
    if not 0 < seconds < float("inf"):
        raise AddressError(f"{TIMEOUT_VARIABLE}={text}: not a positive number of seconds")
    return seconds


def dask_missing() -> str | None:
    """The pip command that installs Dask's distributed scheduler client, if it is missing."""
    if importlib.util.find_spec("distributed") is None:
        return "pip install 'mjcfbuild[dask]'"
    return None


@dataclass(frozen=True)
class SharingChoice:
    """The remote cache and executor one build uses, and where each was set."""

    remote: RemoteSpec | None
    executor: ExecutorSpec
    remote_origin: str = ""
    executor_origin: str = ""


def choose(
    *,
    manifest_remote: str | None,
    manifest_executor: str | None,
    environ: dict[str, str],
    cli_executor: str | None,
    use_remote: bool,
    manifest_label: str,
) -> SharingChoice:
    """Pick and check the remote and executor: the command line wins over the environment,
    which wins over robot.yaml (so CI can set one remote for every robot).

    Raises ``UsageError`` (exit 2) for a bad command-line or environment value and
    ``ManifestError`` (exit 3) for a bad robot.yaml value; the message names where it was set.
    """
    from mjcfbuild.errors import ManifestError, UsageError

    def fail(origin: str, message: str, hint: str | None = None) -> None:
        if origin.startswith(manifest_label):
            raise ManifestError(message, file=origin, hint=hint or f"fix it in {manifest_label}")
        raise UsageError(f"{origin}: {message}", hint=hint)

    remote = None
    remote_origin = ""
    if use_remote:
        if environ.get(REMOTE_VARIABLE, "").strip():
            text, remote_origin = environ[REMOTE_VARIABLE], f"${REMOTE_VARIABLE}"
        elif manifest_remote:
            text, remote_origin = manifest_remote, f"{manifest_label} cache.remote"
        else:
            text = ""
        if text:
            try:
                remote = parse_remote(text)
            except AddressError as exc:
                fail(remote_origin, str(exc))
            assert remote is not None
            for check in (signing_key, remote_timeout):
                try:
                    check(environ)
                except AddressError as exc:
                    raise UsageError(str(exc), hint="fix it, or build with --no-remote") from None
            install = missing_package(remote)
            if install:
                fail(
                    remote_origin,
                    f"a {remote.protocol}:// remote cache needs a package that is not installed",
                    hint=f"{install}, or build with --no-remote",
                )
    if cli_executor:
        text, executor_origin = cli_executor, "--executor"
    elif environ.get(EXECUTOR_VARIABLE, "").strip():
        text, executor_origin = environ[EXECUTOR_VARIABLE], f"${EXECUTOR_VARIABLE}"
    elif manifest_executor:
        text, executor_origin = manifest_executor, f"{manifest_label} executor"
    else:
        text, executor_origin = "local", ""
    executor = ExecutorSpec("local")
    try:
        executor = parse_executor(text)
    except AddressError as exc:
        fail(executor_origin, str(exc))
    if executor.kind == "dask":
        install = dask_missing()
        if install:
            fail(executor_origin, "a Dask executor needs dask.distributed", hint=install)
    return SharingChoice(remote, executor, remote_origin, executor_origin)
