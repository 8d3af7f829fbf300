"""Reading binary STL without trimesh gives exactly what reading it through trimesh gave."""

from __future__ import annotations

import struct
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mjcfbuild.errors import InputError
from mjcfbuild.meshes import load
from mjcfbuild.meshes.load import load_parts
from mjcfbuild.meshes.stlfile import read_binary_stl
from tests.conftest import EXAMPLES
from tests.fuzzing import examples
from tests.meshes.samples import ascii_stl


def binary_stl(path: Path, corners: np.ndarray, attributes: list[int], header: bytes) -> Path:
    """A binary STL of ``corners`` (three rows per triangle) with the given attribute bytes."""
    triangles = corners.reshape(-1, 3, 3).astype("<f4")
    records = b"".join(
        struct.pack("<3f", 0.0, 0.0, 1.0) + triangle.tobytes() + struct.pack("<H", attribute)
        for triangle, attribute in zip(triangles, attributes, strict=True)
    )
    path.write_bytes(header.ljust(80, b" ")[:80] + struct.pack("<I", len(triangles)) + records)
    return path


def parts_through_trimesh(path: Path, monkeypatch) -> list:
    with monkeypatch.context() as patch:
        patch.setattr(load, "_binary_stl_pieces", lambda _: None)
        return load_parts(path)


def assert_same_parts(ours: list, theirs: list) -> None:
    assert len(ours) == len(theirs)
    for mine, other in zip(ours, theirs, strict=True):
        assert mine.rgba == other.rgba
        assert mine.vertices.dtype == other.vertices.dtype
        np.testing.assert_array_equal(mine.vertices, other.vertices)
        np.testing.assert_array_equal(mine.faces, other.faces)


# Coordinates drawn from a few values so that triangles share corners, as real meshes do.
coordinate = st.sampled_from([0.0, -0.0, 1.0, -2.5, 1e-7, 3.25e4, 0.1])
triangles = st.integers(1, 12).flatmap(
    lambda n: st.tuples(
        st.lists(coordinate, min_size=9 * n, max_size=9 * n),
        st.lists(st.integers(0, 0xFFFF), min_size=n, max_size=n),
        st.sampled_from([b"", b"solid part", b"\x00" * 80, b"COLOR=\xff\x00\x00\xff"]),
    )
)


@settings(max_examples=examples(60), deadline=None, suppress_health_check=list(HealthCheck))
@given(triangles)
def test_binary_stl_parts_match_trimesh(monkeypatch, drawn):
    values, attributes, header = drawn
    with tempfile.TemporaryDirectory() as folder:
        path = binary_stl(Path(folder) / "part.stl", np.array(values), attributes, header)
        corners = np.array(values, dtype=np.float32).astype(float).reshape(-1, 3, 3)
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        if not np.any(normals != 0.0):  # both readers refuse a mesh without area
            for read in (
                lambda: load_parts(path),
                lambda: parts_through_trimesh(path, monkeypatch),
            ):
                with pytest.raises(InputError, match="every triangle of the mesh is degenerate"):
                    read()
            return
        assert_same_parts(load_parts(path), parts_through_trimesh(path, monkeypatch))


def test_example_stl_matches_trimesh(monkeypatch):
    path = EXAMPLES / "arm" / "meshes" / "base.stl"
    assert read_binary_stl(path) is not None
    assert_same_parts(load_parts(path), parts_through_trimesh(path, monkeypatch))


def test_ascii_and_mislabelled_files_are_left_to_trimesh(tmp_path):
    text = ascii_stl(tmp_path / "text.stl")
    assert read_binary_stl(text) is None
    assert len(load_parts(text)[0].faces) > 0
    corners = np.eye(3)
    truncated = binary_stl(tmp_path / "short.stl", corners, [0], b"")
    truncated.write_bytes(truncated.read_bytes()[:-1])
    assert read_binary_stl(truncated) is None
    tiny = tmp_path / "tiny.stl"
    tiny.write_bytes(b"solid")
    assert read_binary_stl(tiny) is None


def test_an_empty_binary_stl_has_no_triangles(tmp_path):
    path = binary_stl(tmp_path / "empty.stl", np.zeros((0, 3)), [], b"")
    corners, faces = read_binary_stl(path)
    assert corners.shape == (0, 3) and faces.shape == (0, 3)


def test_reading_a_binary_stl_does_not_import_trimesh(tmp_path):
    import subprocess
    import sys

    path = binary_stl(tmp_path / "part.stl", np.eye(3), [0], b"")
    code = (
        "import sys; from pathlib import Path; from mjcfbuild.meshes.load import load_parts; "
        f"load_parts(Path({str(path)!r})); print('trimesh' in sys.modules)"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.stdout.strip() == "False", result.stderr
