"""A model corrupted by hand fails the check, which names the element and the numbers."""

from __future__ import annotations

import re

import pytest

import mjcfbuild
from mjcfbuild.errors import EXIT_CHECK, EXIT_OK
from tests.conftest import copy_example, run_cli


@pytest.fixture(scope="module")
def built_arm(tmp_path_factory):
    arm = copy_example("arm", tmp_path_factory.mktemp("arm"))
    mjcfbuild.build(arm / "robot.yaml", jobs=2)
    return arm


@pytest.fixture
def arm(built_arm, tmp_path):
    """A private copy of the built arm, outputs and build state included."""
    import shutil

    target = tmp_path / "arm"
    shutil.copytree(built_arm, target)
    return target


def corrupt(arm, old: str, new: str) -> None:
    model = arm / "mjcf" / "example_arm.xml"
    text = model.read_text()
    assert old in text, old
    model.write_text(text.replace(old, new, 1))


def check(arm):
    return run_cli("check", cwd=arm)


def test_the_built_model_passes(arm):
    result = check(arm)
    assert result.code == EXIT_OK, result.stderr
    assert "mjcfbuild: check passed" in result.stdout


def test_a_flipped_joint_axis(arm):
    corrupt(
        arm,
        'frictionloss="0.05" axis="0 1 0" armature="0.024"/>',
        'frictionloss="0.05" axis="0 -1 0" armature="0.024"/>',
    )
    result = check(arm)
    assert result.code == EXIT_CHECK
    assert "joint 'elbow': axis (0, 1, 0) in the URDF, (0, -1, 0) in the model" in result.stderr


def test_a_moved_body(arm):
    corrupt(
        arm, '<body name="forearm_link" pos="0 0 0.3">', '<body name="forearm_link" pos="0 0 0.31">'
    )
    result = check(arm)
    assert result.code == EXIT_CHECK
    match = re.search(r"link '(\w+)' is ([0-9.e-]+) m and", result.stderr)
    assert match and match.group(1) == "forearm_link"
    assert float(match.group(2)) == pytest.approx(0.01, rel=1e-3)
    assert "links below it follow" in result.stderr


def test_a_changed_mass(arm):
    corrupt(arm, '<inertial pos="0 0 0.12" mass="0.8"', '<inertial pos="0 0 0.12" mass="0.4"')
    result = check(arm)
    assert result.code == EXIT_CHECK
    assert (
        "body 'forearm_link': mass 0.8 in the URDF (links camera_link, camera_optical_frame, forearm_link), 0.4 in the model"
        in result.stderr
    )


def test_a_deleted_site(arm):
    corrupt(
        arm,
        '<site name="tool0" class="link_site" pos="0 0 0.04" quat="0.707106781187 0 0 0.707106781187"/>',
        "",
    )
    result = check(arm)
    assert result.code == EXIT_CHECK
    assert "link 'tool0' has no body or site of its name in the model" in result.stderr


def test_a_changed_joint_range(arm):
    corrupt(arm, 'name="shoulder_lift" range="-1.9 1.9"', 'name="shoulder_lift" range="-1.9 1.5"')
    result = check(arm)
    assert (
        "joint 'shoulder_lift': range (-1.9, 1.9) in the URDF, (-1.9, 1.5) in the model"
        in result.stderr
    )
