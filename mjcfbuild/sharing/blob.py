"""A product as one object: how it is sent to a remote cache and back from a cluster.

Layout (all of it covered by the checksum on the first line)::

    MJCFBUILD-PRODUCT 1 <sha256 of the rest> <length of the rest>[ hmac-sha256=<signature>]\\n
    {"key": ..., "summary": {...}, "files": [[name, size], ...]}\\n
    <the files' bytes, one after another, in the listed order>

An object is used only if its first line, length and checksum are right and it names the key
it was asked for: a truncated, corrupted or foreign object is rejected as a whole. The checksum
proves integrity, not origin: anyone who may write to the remote can write a product that
passes it. With a *signing key* (``MJCFBUILD_CACHE_KEY``, or a file named by
``MJCFBUILD_CACHE_KEY_FILE``; see docs/sharing.md) every object also carries an HMAC-SHA256 of
its key and the rest, and one without a valid signature is rejected. The bytes are a function of
the product (and the signing key) alone (files sorted, JSON with sorted keys), so two machines
that upload the same key upload the same object.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import re
from pathlib import Path

MAGIC = b"MJCFBUILD-PRODUCT 1"
_FIRST_LINE = re.compile(
    rb"^MJCFBUILD-PRODUCT 1 ([0-9a-f]{64}) ([0-9]+)(?: hmac-sha256=([0-9a-f]{64}))?$"
)
_SAFE_NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")


class BadObject(ValueError):
    """An object that failed verification; the message says how."""


def signature(secret: bytes, key: str, rest: bytes) -> str:
    """The HMAC-SHA256 that proves an object of ``key`` was written by a holder of ``secret``."""
    return hmac.new(secret, key.encode() + b"\n" + rest, hashlib.sha256).hexdigest()


def pack(key: str, folder: Path, summary: dict, secret: bytes | None = None) -> bytes:
    """The object of the product ``key``: ``summary`` and the files it lists in ``folder``,
    signed with ``secret`` if given."""
    names = sorted(summary.get("files", {}))
    contents = [(folder / name).read_bytes() for name in names]
    header = {
        "key": key,
        "summary": summary,
        "files": [[name, len(data)] for name, data in zip(names, contents, strict=True)],
    }
    rest = json.dumps(header, sort_keys=True, separators=(",", ":")).encode() + b"\n"
    rest += b"".join(contents)
    digest = hashlib.sha256(rest).hexdigest()
    signed = f" hmac-sha256={signature(secret, key, rest)}" if secret else ""
    return MAGIC + f" {digest} {len(rest)}{signed}\n".encode() + rest


def unpack(key: str, data: bytes, folder: Path, secret: bytes | None = None) -> dict:
    """Verify ``data`` as the product ``key``, write its files into ``folder``; its summary.

    Raises :class:`BadObject` (and writes nothing) unless the object is complete, intact and
    the product of ``key`` (and, with ``secret``, signed with it).
    """
    summary, files = verify(key, data, secret)
    folder.mkdir(parents=True, exist_ok=True)
    for name, content in files.items():
        (folder / name).write_bytes(content)
    return summary


def verify(key: str, data: bytes, secret: bytes | None = None) -> tuple[dict, dict[str, bytes]]:
    """The summary and files of a verified object (see :func:`unpack`)."""
    first, newline, rest = data.partition(b"\n")
    match = _FIRST_LINE.match(first)
    if not newline or not match:
        raise BadObject("not an mjcfbuild product")
    digest, length = match.group(1).decode(), int(match.group(2))
    if len(rest) != length:
        raise BadObject(f"truncated ({len(rest)} of {length} bytes)")
    if hashlib.sha256(rest).hexdigest() != digest:
        raise BadObject("corrupted (checksum mismatch)")
    if secret:
        signed = match.group(3)
        if signed is None:
            raise BadObject("unsigned, and a signing key is set")
        if not hmac.compare_digest(signed.decode(), signature(secret, key, rest)):
            raise BadObject("not signed with this signing key")
    header_line, _, body = rest.partition(b"\n")
    try:
        header = json.loads(header_line)
        entries = [(str(name), int(size)) for name, size in header["files"]]
        summary = header["summary"]
        stored_key = header["key"]
    except (ValueError, KeyError, TypeError) as exc:
        raise BadObject(f"unreadable header ({type(exc).__name__})") from None
    if stored_key != key:
        raise BadObject(f"the product of another key ({str(stored_key)[:12]}...)")
    files: dict[str, bytes] = {}
    offset = 0
    for name, size in entries:
        if not _SAFE_NAME.match(name):
            raise BadObject(f"unsafe file name '{name[:40]}'")
        files[name] = body[offset : offset + size]
        offset += size
    if offset != len(body) or set(files) != set(summary.get("files", {})):
        raise BadObject("its files do not match its summary")
    for name, content in files.items():
        if hashlib.md5(content, usedforsecurity=False).hexdigest() != summary["files"][name]:
            raise BadObject(f"{name} does not match its digest")
    return summary, files
