"""Applying inputs: merged defaults, names checked with the ones that exist listed."""

from __future__ import annotations

import pytest

import mjcfbuild
from mjcfbuild.errors import BuildFailed
from tests.conftest import two_link_urdf, write


def build(tmp_path, inputs: str):
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "inputs.xml", f"<mujoco_inputs>{inputs}</mujoco_inputs>")
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\nmujoco_inputs: {file: inputs.xml}\n",
    )
    return mjcfbuild.build(tmp_path / "robot.yaml")


def error(tmp_path, inputs: str) -> str:
    with pytest.raises(BuildFailed) as info:
        build(tmp_path, inputs)
    return info.value.one_line()


def test_unknown_joint_in_an_actuator_names_element_line_and_existing_joints(tmp_path):
    text = error(
        tmp_path,
        '<raw_inputs>\n<actuator>\n<motor name="m" joint="elbow"/></actuator></raw_inputs>',
    )
    assert "inputs.xml:3: <motor 'm'> joint=\"elbow\" names a joint that does not exist" in text
    assert "joint names: hinge" in text


def test_unknown_body_in_an_exclude(tmp_path):
    text = error(
        tmp_path,
        '<raw_inputs><contact>\n<exclude body1="base" body2="hand"/></contact></raw_inputs>',
    )
    assert 'inputs.xml:2: <exclude> body2="hand" names a body that does not exist' in text
    assert "body names: arm, base, world" in text


def test_unknown_modify_target_lists_what_exists(tmp_path):
    text = error(
        tmp_path,
        '<processed_inputs>\n<modify_element type="joint" name="nope" damping="1"/></processed_inputs>',
    )
    assert "modify_element: no joint named 'nope'" in text and "joint names: hinge" in text


def test_camera_at_unknown_link(tmp_path):
    text = error(tmp_path, '<processed_inputs>\n<camera site="eye" name="c"/></processed_inputs>')
    assert (
        "camera refers to link 'eye', which does not exist" in text and "links: arm, base" in text
    )


def test_input_defaults_merge_into_mjcfbuilds_classes_and_new_classes_are_added(tmp_path):
    result = build(
        tmp_path,
        '<raw_inputs><default><default class="visual"><geom group="1"/></default>'
        '<default class="heavy"><joint damping="5"/></default></default>'
        '<sensor><jointpos name="q" joint="hinge"/></sensor></raw_inputs>',
    )
    text = result.robot.read_text()
    assert text.count('<default class="visual">') == 1
    assert '<default class="heavy">' in text
    assert any("default class 'visual' sets geom group='1'" in w for w in result.warnings)
