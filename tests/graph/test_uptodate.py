"""The up-to-date checks' reasons, which explain, build -n and check --up-to-date print."""

from __future__ import annotations

import hashlib

from mjcfbuild.graph.hashes import HashCache
from mjcfbuild.graph.uptodate import outputs_intact


def _reason(path, written: bytes) -> str:
    check = outputs_intact(HashCache(None))
    digest = hashlib.md5(written).hexdigest()
    assert check(None, {"outputs": {str(path): digest}}) is False
    return check.reason  # type: ignore[attr-defined]


def test_a_changed_record_of_the_build_is_not_called_an_edit(tmp_path):
    """An interrupted build leaves its records and pictures changed: the reason said they
    were edited and that a build would stop at them (none does)."""
    state = tmp_path / "mjcf" / ".mjcfbuild" / "products" / "forearm"
    state.mkdir(parents=True)
    (state / "part1.msh").write_bytes(b"new")
    picture = tmp_path / "mjcf" / "report" / "previews" / "side.png"
    picture.parent.mkdir(parents=True)
    picture.write_bytes(b"new")
    for path in (state / "part1.msh", picture):
        assert _reason(path, b"old") == (
            f"output changed since its task last finished (a build cut short): {path}"
        )
    model = tmp_path / "mjcf" / "robot.xml"
    model.write_bytes(b"tuned")
    assert _reason(model, b"built").startswith("output edited since it was built:")
