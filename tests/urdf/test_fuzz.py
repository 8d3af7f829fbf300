"""Fuzzing URDFs: any document either becomes a model MuJoCo loads, or fails with one of the
documented errors (never an internal error, never a MuJoCo exception)."""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

from mjcfbuild.errors import InternalError, MjcfbuildError
from tests.meshes.samples import ascii_stl
from tests.mjcf.helpers import build
from tests.strategies import urdf_text


@pytest.fixture(scope="module")
def description() -> Path:
    """A folder with the one mesh the generated URDFs may use (also one level up)."""
    root = Path(tempfile.mkdtemp(prefix="mjcfbuild-fuzz-"))
    folder = root / "description"
    folder.mkdir()
    ascii_stl(folder / "part.stl")
    ascii_stl(root / "part.stl")
    return folder


@settings(max_examples=250, deadline=None, suppress_health_check=list(HealthCheck))
@given(urdf_text())
def test_any_urdf_builds_or_fails_with_a_documented_error(description, text):
    try:
        _, model = build(text, description)
    except MjcfbuildError as error:
        assert not isinstance(error, InternalError), error.one_line()
        assert error.location is not None, error.one_line()
        assert "\n" not in error.one_line()
    else:
        assert model.nbody >= 1
