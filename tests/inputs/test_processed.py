"""One model per processed tag: robot.yaml, <processed_inputs> and the plan read the same one."""

from __future__ import annotations

import typing

import pytest
from lxml import etree

from mjcfbuild.errors import InputError, ManifestError
from mjcfbuild.inputs.model import Inputs, inputs_from_dict
from mjcfbuild.inputs.processed import (
    PROCESSED_INPUTS,
    CameraInput,
    DecomposeInput,
    LidarInput,
    ModifyInput,
    processed_tag,
)
from mjcfbuild.manifest.loading import parse_manifest
from mjcfbuild.manifest.models import MujocoInputs
from mjcfbuild.manifest.mujoco_inputs import native_inputs

# The same four items, as the reference converter's XML and as robot.yaml says them.
XML = {
    "camera": '<camera site="eye_optical" name="eye" fovy="58" mode="fixed"/>',
    "lidar": '<lidar ref_site="laser" sensor_name="rf" min_angle="-0.3" max_angle="0.3" '
    'angle_increment="0.025"/>',
    "decompose_mesh": '<decompose_mesh mesh_name="forearm" threshold="0.02"/>',
    "modify_element": '<modify_element type="geom" mesh="hand" class="collision" '
    'contype="0" name="ignored for a geom"/>',
}
YAML = """name: r
source: {urdf: r.urdf}
mujoco_inputs:
  cameras: [{name: eye, link: eye_optical, attributes: {fovy: '58', mode: fixed}}]
  lidars:
    - {sensor_name: rf, link: laser, min_angle: -0.3, max_angle: 0.3, angle_increment: 0.025}
  decompose: [{mesh: forearm, threshold: 0.02}]
  modify: [{type: geom, mesh: hand, class: collision, attributes: {contype: '0'}}]
"""


def from_xml(text: str):
    element = etree.fromstring(f"<processed_inputs>\n{text}</processed_inputs>")[0]
    kind = processed_tag(element.tag)
    assert kind is not None
    return kind.from_xml(element, "inputs.xml")


def test_robot_yaml_lists_each_registered_tag_by_its_model():
    fields = MujocoInputs.model_fields
    assert set(fields) == {"file", "raw"} | {kind.manifest_key for kind in PROCESSED_INPUTS}
    for kind in PROCESSED_INPUTS:
        assert typing.get_args(fields[kind.manifest_key].annotation) == (kind,)


@pytest.mark.parametrize("tag", list(XML))
def test_xml_and_robot_yaml_give_the_same_item(tag):
    item = from_xml(XML[tag])
    assert item.origin == "inputs.xml:2"
    settings = parse_manifest(YAML).mujoco_inputs
    (same,) = native_inputs(settings, "robot.yaml").of(type(item))
    assert same.model_dump() == item.model_dump()
    assert same.origin == f"robot.yaml mujoco_inputs.{type(item).manifest_key}[0]"


def test_the_plan_keeps_every_item_and_where_it_was_given():
    inputs = Inputs(processed=[from_xml(text) for text in XML.values()])
    again = inputs_from_dict(inputs.to_dict())
    assert [item.model_dump() for item in again.processed] == [
        item.model_dump() for item in inputs.processed
    ]
    assert [item.origin for item in again.processed] == ["inputs.xml:2"] * 4
    assert [type(item) for item in again.processed] == [
        CameraInput,
        LidarInput,
        DecomposeInput,
        ModifyInput,
    ]


@pytest.mark.parametrize(
    ("xml", "yaml", "message"),
    [
        (
            '<lidar ref_site="l" sensor_name="r" min_angle="1" max_angle="0" angle_increment="1"/>',
            "lidars: [{sensor_name: r, link: l, min_angle: 1, max_angle: 0, angle_increment: 1}]",
            "max_angle is below min_angle",
        ),
        (
            '<lidar ref_site="l" sensor_name="r" min_angle="0" max_angle="inf" angle_increment="1"/>',
            "lidars: [{sensor_name: r, link: l, min_angle: 0, max_angle: .inf, angle_increment: 1}]",
            "finite number",
        ),
        (
            '<decompose_mesh mesh_name="m" threshold=" "/>',
            "decompose: [{mesh: m, threshold: ''}]",
            "expected a number, got ''",
        ),
        (
            '<camera site="l" name=" "/>',
            "cameras: [{name: '', link: l}]",
            "expected a non-empty string, got ''",
        ),
        (
            '<decompose_mesh mesh_name="m" threshold="0"/>',
            "decompose: [{mesh: m, threshold: 0}]",
            "should be greater than 0",
        ),
        (
            '<modify_element type="joint" damping="1"/>',
            "modify: [{type: joint, attributes: {damping: 1}}]",
            # the model's check, said in each form's words
            ("needs a 'name' attribute", "a joint is found by 'name', and 'name' is missing"),
        ),
    ],
)
def test_both_forms_are_validated_by_the_one_model(xml, yaml, message):
    in_xml, in_yaml = message if isinstance(message, tuple) else (message, message)
    with pytest.raises(InputError) as from_file:
        from_xml(xml)
    assert in_xml in from_file.value.one_line()
    assert from_file.value.location.line == 2
    with pytest.raises(ManifestError) as from_manifest:
        parse_manifest(f"name: r\nsource: {{urdf: r.urdf}}\nmujoco_inputs:\n  {yaml}\n")
    assert in_yaml in from_manifest.value.one_line()


LIDAR = 'sensor_name="r" min_angle="0" max_angle="1" angle_increment="1"'
LIDAR_YAML = "sensor_name: r, min_angle: 0, max_angle: 1, angle_increment: 1"


@pytest.mark.parametrize(
    ("xml", "yaml", "in_xml", "in_yaml"),
    [
        (
            f'<lidar ref_site="l" {LIDAR} range="5"/>',
            f"lidars: [{{link: l, {LIDAR_YAML}, range: 5}}]",
            "<lidar> has no attribute 'range' (known attributes: angle_increment, max_angle, "
            "min_angle, ref_site, sensor_name)",
            "unknown key 'range'; allowed keys: angle_increment, link, max_angle, min_angle, "
            "sensor_name",
        ),
        (  # each form's name for the frame, written in the other
            f'<lidar link="l" {LIDAR}/>',
            f"lidars: [{{ref_site: l, {LIDAR_YAML}}}]",
            "<lidar> has no attribute 'link'; did you mean 'ref_site'?",
            "unknown key 'ref_site'; did you mean 'link'?",
        ),
        (
            f'<lidar ref_site="l" {LIDAR} angle_incrment="1"/>',
            f"lidars: [{{link: l, {LIDAR_YAML}, angle_incrment: 1}}]",
            "<lidar> has no attribute 'angle_incrment'; did you mean 'angle_increment'?",
            "unknown key 'angle_incrment'; did you mean 'angle_increment'?",
        ),
        (
            '<decompose_mesh mesh_name="m" treshold="0.1"/>',
            "decompose: [{mesh: m, treshold: 0.1}]",
            "<decompose_mesh> has no attribute 'treshold'; did you mean 'threshold'? "
            "(known attributes: mesh_name, threshold)",
            "unknown key 'treshold'; did you mean 'threshold'? allowed keys: mesh, threshold",
        ),
        (
            '<decompose_mesh mesh="m"/>',
            "decompose: [{mesh_name: m}]",
            "<decompose_mesh> has no attribute 'mesh'; did you mean 'mesh_name'?",
            "unknown key 'mesh_name'; did you mean 'mesh'?",
        ),
    ],
)
def test_lidar_and_decompose_refuse_what_they_do_not_know_in_both_forms(xml, yaml, in_xml, in_yaml):
    with pytest.raises(InputError) as from_file:
        from_xml(xml)
    assert from_file.value.one_line().startswith(f"inputs.xml:2: {in_xml}")
    with pytest.raises(ManifestError) as from_manifest:
        parse_manifest(f"name: r\nsource: {{urdf: r.urdf}}\nmujoco_inputs:\n  {yaml}\n")
    assert from_manifest.value.location.line == 4
    assert in_yaml in from_manifest.value.one_line()


@pytest.mark.parametrize("tag", ["lidar", "decompose_mesh"])
def test_every_attribute_the_reference_converter_reads_is_known(tag):
    """Its make_mjcf_from_robot_description reads these attributes of the two tags and no
    other (ref_site, sensor_name, min_angle, max_angle, angle_increment; mesh_name, threshold)."""
    reads = {
        "lidar": ["ref_site", "sensor_name", "min_angle", "max_angle", "angle_increment"],
        "decompose_mesh": ["mesh_name", "threshold"],
    }[tag]
    kind = processed_tag(tag)
    assert kind is not None and sorted(kind.xml_fields) == sorted(reads)
    assert from_xml(XML[tag]).origin == "inputs.xml:2"


def test_robot_yaml_camera_settings_become_mjcf_text_after_the_attributes():
    camera = CameraInput(
        name="c",
        link="l",
        fovy=58,
        resolution=(640, 480),
        attributes={"fovy": "1", "orthographic": True, "ipd": 0.068},
    )
    assert camera.mjcf_attributes() == {
        "fovy": "58.0",
        "orthographic": "true",
        "ipd": "0.068",
        "resolution": "640 480",
    }


def test_an_origin_is_not_a_robot_yaml_key():
    with pytest.raises(ManifestError, match="unknown key 'origin'"):
        parse_manifest(
            "name: r\nsource: {urdf: r.urdf}\n"
            "mujoco_inputs: {decompose: [{mesh: m, origin: 'x.xml:1'}]}\n"
        )
