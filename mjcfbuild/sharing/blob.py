"""A product as one object: how it is sent to a remote cache and back from a cluster.

Layout (all of it covered by the checksum on the first line)::

    MJCFBUILD-PRODUCT 1 <sha256 of the rest> <length of the rest>\\n
    {"key": ..., "summary": {...}, "files": [[name, size], ...]}\\n
    <the files' bytes, one after another, in the listed order>

An object is used only if its first line, length and checksum are right and it names the key
it was asked for: a truncated, corrupted or foreign object is rejected as a whole. The bytes are
a function of the product alone (files sorted, JSON with sorted keys), so two machines that
upload the same key upload the same object.
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

MAGIC = b"MJCFBUILD-PRODUCT 1"
_FIRST_LINE = re.compile(rb"^MJCFBUILD-PRODUCT 1 ([0-9a-f]{64}) ([0-9]+)$")
_SAFE_NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")


class BadObject(ValueError):
    """An object that failed verification; the message says how."""


def pack(key: str, folder: Path, summary: dict) -> bytes:
    """The object of the product ``key``: ``summary`` and the files it lists in ``folder``."""
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
    return MAGIC + f" {digest} {len(rest)}\n".encode() + rest


def unpack(key: str, data: bytes, folder: Path) -> dict:
    """Verify ``data`` as the product ``key``, write its files into ``folder``; its summary.

    Raises :class:`BadObject` (and writes nothing) unless the object is complete, intact and
    the product of ``key``.
    """
    summary, files = verify(key, data)
    folder.mkdir(parents=True, exist_ok=True)
    for name, content in files.items():
        (folder / name).write_bytes(content)
    return summary


def verify(key: str, data: bytes) -> tuple[dict, dict[str, bytes]]:
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
