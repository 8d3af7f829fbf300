"""The up-to-date checks' reasons, which explain, build -n and check --up-to-date print."""

from __future__ import annotations

import hashlib

from mjcfbuild.graph.hashes import HashCache
from mjcfbuild.graph.uptodate import outputs_intact


def _reason(path, out_dir, written: bytes) -> str:
    check = outputs_intact(HashCache(None), out_dir)
    digest = hashlib.md5(written).hexdigest()
    assert check(None, {"outputs": {str(path): digest}}) is False
    return check.reason  # type: ignore[attr-defined]


def test_a_changed_record_of_the_build_is_not_called_an_edit(tmp_path):
    """An interrupted build leaves its records and pictures changed: the reason said they
    were edited and that a build would stop at them (none does). Only the folders in the
    output folder count: a project in a folder named report/ has its model edits named."""
    out = tmp_path / "report" / "arm" / "mjcf"
    state = out / ".mjcfbuild" / "products" / "forearm"
    state.mkdir(parents=True)
    (state / "part1.msh").write_bytes(b"new")
    picture = out / "report" / "previews" / "side.png"
    picture.parent.mkdir(parents=True)
    picture.write_bytes(b"new")
    for path in (state / "part1.msh", picture):
        assert _reason(path, out, b"old") == (
            f"output changed since its task last finished (a build cut short): {path}"
        )
    model = out / "robot.xml"
    model.write_bytes(b"tuned")
    assert _reason(model, out, b"built").startswith("output edited since it was built:")
