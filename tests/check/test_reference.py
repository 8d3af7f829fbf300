"""The check's reference kinematics come from a reader independent of mjcfbuild's parser."""

from __future__ import annotations

from mjcfbuild.check.model_check import check_model
from mjcfbuild.urdf.model import Pose
from mjcfbuild.urdf.parse import parse_urdf
from tests.check.test_check_command import ROUNDED_MJCF, ROUNDED_URDF
from tests.conftest import write


def _model_of_the_parse(tmp_path, elbow_z: str):
    """The model a build makes of a parse that put the elbow at ``elbow_z``."""
    text = ROUNDED_MJCF.replace("TOOL", '<site name="tool" pos="0 0 -0.2"/>').replace(
        '<body name="lower" pos="0 0 -0.2">', f'<body name="lower" pos="0 0 {elbow_z}">'
    )
    return write(tmp_path / "arm.xml", text)


def test_a_parser_bug_that_the_build_shares_is_caught(tmp_path):
    robot = parse_urdf(ROUNDED_URDF.encode(), "arm.urdf")
    elbow = next(joint for joint in robot.joints if joint.name == "elbow")
    elbow.origin = Pose((0.0, 0.0, -0.3))  # as if the parser misread the elbow's origin
    model = _model_of_the_parse(tmp_path, "-0.3")  # and the build followed the parse
    report = check_model(robot, model, model, set(), urdf=ROUNDED_URDF.encode())
    assert report.results["kinematics"]["reference"] == "yourdfpy"
    assert any(f.startswith("link 'lower' is 0.1 m") for f in report.failures), report.failures


def test_the_correct_model_passes_and_an_unreadable_text_falls_back(tmp_path):
    robot = parse_urdf(ROUNDED_URDF.encode(), "arm.urdf")
    model = _model_of_the_parse(tmp_path, "-0.2")
    assert check_model(robot, model, model, set(), urdf=ROUNDED_URDF.encode()).passes
    fallback = check_model(robot, model, model, set(), urdf=b"<robot")
    assert fallback.passes
    assert fallback.results["kinematics"]["reference"].startswith("mjcfbuild's URDF parser")
