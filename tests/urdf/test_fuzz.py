"""Fuzzing URDFs: any document either becomes a model MuJoCo loads, or fails with one of the
documented errors (never an internal error, never a MuJoCo exception)."""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

from mjcfbuild.errors import InternalError, MjcfbuildError
from tests.fuzzing import examples
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


@settings(max_examples=examples(250), deadline=None, suppress_health_check=list(HealthCheck))
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


def test_a_very_long_thin_cylinder_keeps_its_radius(description):
    """Found by the fuzz test: MuJoCo's writer printed radius 0.1 beside 1.25e11 as 0."""
    text = (
        '<robot name="r"><link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<collision><geometry><cylinder radius="0.1" length="2.5e11"/></geometry></collision>'
        "</link></robot>"
    )
    _, model = build(text, description)
    assert model.geom_size[0][:2].tolist() == [0.1, 1.25e11]


def test_a_centre_of_mass_kilometres_away_is_named_at_the_joint_it_leaves_unsized(description):
    """Found by the fuzz test: a link's centre of mass 2,048 km out rounded away the inertia a
    joint moves (-3e-09), and MuJoCo refused the negative gains sized from it, unplaced."""
    text = (
        '<robot name="fuzz"><link name="base"><inertial><origin xyz="0.0 1.0 2047975.0"/>'
        '<mass value="0.5"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/>'
        '</inertial></link>\n<link name="l1"></link>\n'
        '<joint name="j0" type="continuous"><parent link="base"/><child link="l1"/></joint>'
        "</robot>"
    )
    with pytest.raises(MjcfbuildError) as raised:
        build(text, description)
    assert raised.value.one_line().startswith("robot.urdf:3: joint 'j0' moves an inertia MuJoCo")


def test_property_tests_are_deterministic_by_default():
    """A clean clone runs the same examples every time; MJCFBUILD_FUZZ asks for random ones."""
    from hypothesis import settings

    from tests.fuzzing import fuzz_factor

    if fuzz_factor():
        pytest.skip("MJCFBUILD_FUZZ is set: this is the long randomized run")
    assert settings.default.derandomize is True
    assert settings.default.database is None
