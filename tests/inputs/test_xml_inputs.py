"""Reading <mujoco_inputs>: every item with its line; defects are errors at their line."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.inputs.processed import CameraInput, DecomposeInput, LidarInput, ModifyInput
from mjcfbuild.inputs.xml_inputs import read_inputs_file
from tests.conftest import EXAMPLES, write


def test_reference_inputs_file():
    inputs = read_inputs_file(EXAMPLES / "reference_demo" / "test_inputs.xml", "test_inputs.xml")
    sections = [item.section for item in inputs.raw]
    assert sections.count("actuator") == 3 and sections.count("sensor") == 4
    assert sections.count("default") == 2 and "option" in sections
    (camera,) = inputs.of(CameraInput)
    assert (camera.name, camera.link) == ("camera", "camera_color_optical_frame")
    # the XML form's camera attributes are applied as written, not as robot.yaml's numbers
    assert camera.attributes == {"fovy": "58", "mode": "fixed", "resolution": "640 480"}
    (lidar,) = inputs.of(LidarInput)
    assert (lidar.sensor_name, lidar.angle_increment) == ("rf", 0.025)
    assert [m.describe() for m in inputs.of(ModifyInput)] == ["joint 'joint1'", "body 'forearm'"]
    assert inputs.of(ModifyInput)[0].attributes == {"frictionloss": "1.0", "damping": "2.0"}
    assert inputs.raw[0].origin == "test_inputs.xml:5"


def inputs_file(tmp_path, body):
    return write(tmp_path / "inputs.xml", f"<mujoco_inputs>\n{body}\n</mujoco_inputs>")


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ("<raw_inputs>\n<worldbody/></raw_inputs>", "raw_inputs cannot hold <worldbody>"),
        ("<processed_inputs>\n<camera name='c'/></processed_inputs>", "needs a 'site' attribute"),
        (
            "<processed_inputs>\n<lidar ref_site='l' sensor_name='r' min_angle='0' max_angle='1' angle_increment='0'/></processed_inputs>",
            "angle_increment: '0' should be greater than 0",
        ),
        (
            "<processed_inputs>\n<lidar ref_site='l' sensor_name='r' min_angle='x' max_angle='1' angle_increment='1'/></processed_inputs>",
            "min_angle: expected a number, got 'x'",
        ),
        (
            "<processed_inputs>\n<modify_element type='geom' mesh='m' damping='1'/></processed_inputs>",
            "needs a 'class' attribute",
        ),
        (
            "<processed_inputs>\n<modify_element type='joint' name='j'/></processed_inputs>",
            "sets no attribute",
        ),
        (
            "<processed_inputs>\n<decompose_mesh mesh_name='m' threshold='2'/></processed_inputs>",
            "threshold: '2' should be less than or equal to 1",
        ),
        (
            "<processed_inputs>\n<teleport/></processed_inputs>",
            "processed_inputs cannot hold <teleport>",
        ),
        ("\n<extras/>", "<mujoco_inputs> cannot hold <extras>"),
    ],
)
def test_defects_are_errors_at_their_line(tmp_path, body, message):
    with pytest.raises(InputError) as info:
        read_inputs_file(inputs_file(tmp_path, body), "inputs.xml")
    assert message in info.value.one_line()
    assert info.value.location.line == 3


def test_decompose_mesh_threshold_defaults_to_0_05(tmp_path):
    path = inputs_file(
        tmp_path, "<processed_inputs><decompose_mesh mesh_name='forearm'/></processed_inputs>"
    )
    (item,) = read_inputs_file(path, "inputs.xml").of(DecomposeInput)
    assert (item.mesh, item.threshold) == ("forearm", 0.05)


def test_a_urdf_can_serve_as_inputs_file_and_other_roots_are_refused(tmp_path):
    urdf = write(
        tmp_path / "r.urdf",
        "<robot name='r'><link name='a'/><mujoco_inputs><raw_inputs><option timestep='0.001'/></raw_inputs></mujoco_inputs></robot>",
    )
    assert read_inputs_file(urdf, "r.urdf").raw[0].section == "option"
    with pytest.raises(InputError, match="root element is <mujoco>"):
        read_inputs_file(write(tmp_path / "m.xml", "<mujoco/>"), "m.xml")
