"""Product objects: what is packed comes back only whole, intact and under its own key."""

from __future__ import annotations

import hashlib

import pytest

from mjcfbuild.sharing.blob import BadObject, pack, unpack, verify

KEY = "ab" * 32


def product(folder):
    folder.mkdir(parents=True, exist_ok=True)
    files = {"mesh.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "texture0.png": bytes(range(256))}
    for name, data in files.items():
        (folder / name).write_bytes(data)
    digests = {n: hashlib.md5(d, usedforsecurity=False).hexdigest() for n, d in files.items()}
    return {"files": digests, "parts": [{"file": "mesh.obj"}]}


def test_round_trip_and_same_bytes_every_time(tmp_path):
    summary = product(tmp_path / "made")
    data = pack(KEY, tmp_path / "made", summary)
    assert data == pack(KEY, tmp_path / "made", summary)
    assert unpack(KEY, data, tmp_path / "back") == summary
    for name in summary["files"]:
        assert (tmp_path / "back" / name).read_bytes() == (tmp_path / "made" / name).read_bytes()


@pytest.mark.parametrize(
    ("damage", "reason"),
    [
        (lambda d: d[:-1], "truncated"),
        (lambda d: d[:40], "not an mjcfbuild product"),
        (lambda d: d[:-5] + bytes([d[-5] ^ 1]) + d[-4:], "corrupted"),
        (lambda d: b"<html>503 Service Unavailable</html>", "not an mjcfbuild product"),
        (lambda d: b"", "not an mjcfbuild product"),
    ],
)
def test_damaged_objects_are_refused_and_write_nothing(tmp_path, damage, reason):
    summary = product(tmp_path / "made")
    data = damage(pack(KEY, tmp_path / "made", summary))
    with pytest.raises(BadObject, match=reason):
        unpack(KEY, data, tmp_path / "back")
    assert not (tmp_path / "back").exists()


def test_an_object_of_another_key_is_refused(tmp_path):
    summary = product(tmp_path / "made")
    with pytest.raises(BadObject, match="another key"):
        verify("cd" * 32, pack(KEY, tmp_path / "made", summary))


def test_a_local_file_that_no_longer_matches_its_summary_is_never_shared(tmp_path):
    summary = product(tmp_path / "made")
    (tmp_path / "made" / "mesh.obj").write_bytes(b"edited by hand\n")
    with pytest.raises(BadObject, match=r"mesh\.obj does not match"):
        verify(KEY, pack(KEY, tmp_path / "made", summary))


SIGNING = b"team-signing-key-" + b"x" * 16


def test_a_signed_object_is_used_only_with_a_valid_signature(tmp_path):
    summary = product(tmp_path / "made")
    signed = pack(KEY, tmp_path / "made", summary, SIGNING)
    assert signed.partition(b"\n")[0].count(b" hmac-sha256=") == 1
    assert signed == pack(KEY, tmp_path / "made", summary, SIGNING)  # still the same bytes
    assert unpack(KEY, signed, tmp_path / "back", SIGNING) == summary
    assert verify(KEY, signed)[0] == summary  # without a key the checksum alone decides
    with pytest.raises(BadObject, match="unsigned"):
        verify(KEY, pack(KEY, tmp_path / "made", summary), SIGNING)
    with pytest.raises(BadObject, match="not signed with this signing key"):
        verify(KEY, pack(KEY, tmp_path / "made", summary, b"another-key-" + b"y" * 16), SIGNING)
    # A signature covers the key: an object's signature on the product of another key fails.
    other = "cd" * 32
    signature_line = signed.partition(b"\n")[0]
    moved = pack(other, tmp_path / "made", summary, SIGNING).partition(b"\n")[2]
    moved_line = pack(other, tmp_path / "made", summary).partition(b"\n")[0]
    forged = moved_line + b" " + signature_line.rpartition(b" ")[2] + b"\n" + moved
    with pytest.raises(BadObject, match="not signed with this signing key"):
        verify(other, forged, SIGNING)
