"""Joining URDF parts: prefixed names, rebased files, the fixed joint, and bad attachments."""

from __future__ import annotations

from pathlib import Path

import pytest
from lxml import etree

from mjcfbuild.compose.urdf import Part, compose
from mjcfbuild.errors import InputError, ManifestError

MAIN = b"""<robot name="arm">
  <link name="base"/><link name="tool"/>
  <joint name="wrist" type="revolute"><parent link="base"/><child link="tool"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""

HAND = b"""<robot name="hand">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
  <link name="palm"><visual><geometry><mesh filename="meshes/palm.stl"/></geometry>
    <material name="grey"/></visual></link>
  <link name="jaw"><visual><geometry><mesh filename="package://hand/jaw.stl"/></geometry>
    </visual></link>
  <joint name="jaw_joint" type="prismatic"><parent link="palm"/><child link="jaw"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.1" effort="1" velocity="1"/></joint>
  <joint name="jaw2_joint" type="prismatic"><parent link="palm"/><child link="jaw2"/>
    <mimic joint="jaw_joint"/></joint>
  <link name="jaw2"/>
  <ros2_control name="hand" type="system"><joint name="jaw_joint">
    <command_interface name="position"/></joint></ros2_control>
  <gazebo reference="palm"><sensor name="palm_camera" type="camera"/></gazebo>
  <gazebo><plugin name="hand_controller" filename="libhand.so"/></gazebo>
  <sensor name="jaw_ft" type="force_torque"><parent joint="jaw_joint"/></sensor>
</robot>"""


def part(tmp_path: Path, **changes) -> Part:
    def resolve(uri: str) -> Path:
        if uri.startswith("package://hand/"):
            return tmp_path / "hand_pkg" / uri[len("package://hand/") :]
        return tmp_path / "parts" / uri

    values = dict(
        xml=HAND,
        label="hand.urdf",
        key="robot.yaml attach[0]",
        prefix="hand_",
        to="tool",
        xyz=(0.0, 0.0, 0.1),
        rpy=(0.0, 0.0, 0.5),
        resolve=resolve,
    )
    values.update(changes)
    return Part(**values)


def test_part_names_get_the_prefix_and_a_fixed_joint_holds_its_root(tmp_path):
    text, warnings = compose(MAIN, "arm.urdf", [part(tmp_path)], tmp_path / "main")
    root = etree.fromstring(text)
    assert [link.get("name") for link in root.findall("link")] == [
        "base",
        "tool",
        "hand_palm",
        "hand_jaw",
        "hand_jaw2",
    ]
    joint = root.find("joint[@name='hand_attachment']")
    assert joint.get("type") == "fixed"
    assert joint.find("parent").get("link") == "tool"
    assert joint.find("child").get("link") == "hand_palm"
    assert joint.find("origin").get("xyz") == "0.0 0.0 0.1"
    assert joint.find("origin").get("rpy") == "0.0 0.0 0.5"
    assert root.find("joint[@name='hand_jaw2_joint']/mimic").get("joint") == "hand_jaw_joint"
    assert root.find("joint[@name='hand_jaw_joint']/parent").get("link") == "hand_palm"
    assert root.find("material").get("name") == "hand_grey"
    assert root.find("link[@name='hand_palm']/visual/material").get("name") == "hand_grey"
    assert root.find("ros2_control/joint").get("name") == "hand_jaw_joint"
    # The Gazebo sensors of the part's links and its URDF sensors come along, prefixed; a
    # <gazebo> without a reference (the part's own simulation plugins) does not.
    (gazebo,) = root.findall("gazebo")
    assert gazebo.get("reference") == "hand_palm"
    assert gazebo.find("sensor").get("name") == "hand_palm_camera"
    sensor = root.find("sensor")
    assert sensor.get("name") == "hand_jaw_ft"
    assert sensor.find("parent").get("joint") == "hand_jaw_joint"
    assert warnings == [
        "hand.urdf: the part's <gazebo> without a reference left out (only its links, joints, "
        "materials, transmissions, ros2_control, sensors and the <gazebo> elements of its "
        "links are attached)"
    ]


def test_part_files_become_paths_relative_to_the_main_source(tmp_path):
    text, _ = compose(MAIN, "arm.urdf", [part(tmp_path)], tmp_path / "main")
    files = [m.get("filename") for m in etree.fromstring(text).iter("mesh")]
    assert files == ["../parts/meshes/palm.stl", "../hand_pkg/jaw.stl"]


def test_a_part_attaches_to_another_part_whatever_their_order(tmp_path):
    second = part(tmp_path, prefix="left_", to="hand_jaw", key="robot.yaml attach[0]")
    first = part(tmp_path, key="robot.yaml attach[1]")
    root = etree.fromstring(compose(MAIN, "arm.urdf", [second, first], tmp_path)[0])
    joint = root.find("joint[@name='left_attachment']")
    assert joint.find("parent").get("link") == "hand_jaw"
    assert joint.find("child").get("link") == "left_palm"


def test_unknown_to_link_lists_the_links(tmp_path):
    with pytest.raises(ManifestError) as caught:
        compose(MAIN, "arm.urdf", [part(tmp_path, to="flange")], tmp_path)
    assert caught.value.location.file == "robot.yaml attach[0].to"
    assert "'flange'" in caught.value.message and "base, tool" in caught.value.hint


def test_parts_attached_to_each_other_are_a_cycle(tmp_path):
    a = part(tmp_path, prefix="a_", to="b_palm")
    b = part(tmp_path, prefix="b_", to="a_jaw", key="robot.yaml attach[1]")
    with pytest.raises(ManifestError, match=r"cycle: a_ \(to b_palm\) -> b_ \(to a_jaw\)"):
        compose(MAIN, "arm.urdf", [a, b], tmp_path)


def test_a_prefix_that_makes_names_collide_is_refused(tmp_path):
    main = MAIN.replace(b'<link name="tool"/>', b'<link name="tool"/><link name="x_palm"/>')
    with pytest.raises(ManifestError, match="link name 'x_palm'") as caught:
        compose(main, "arm.urdf", [part(tmp_path, prefix="x_")], tmp_path)
    assert caught.value.location.file == "robot.yaml attach[0].prefix"


def test_a_part_with_two_roots_names_its_file(tmp_path):
    xml = HAND.replace(b'<link name="jaw2"/>', b'<link name="jaw2"/><link name="loose"/>')
    with pytest.raises(InputError, match="2 root links") as caught:
        compose(MAIN, "arm.urdf", [part(tmp_path, xml=xml)], tmp_path)
    assert caught.value.location.file == "hand.urdf"


@pytest.mark.parametrize(
    ("main", "warned"),
    [
        (MAIN.replace(b"<link", b"<!-- caf\xe9 -->\n<link", 1), "byte 0xe9 is not UTF-8"),
        (MAIN + b'\n<robot name="spare"/>', "a second root element <robot>"),
    ],
)
def test_a_main_urdf_is_read_as_the_plan_reads_it_with_its_warnings(main, warned, tmp_path):
    # The plan reads what MuJoCo's parser reads past (a Latin-1 byte, a second root) with a
    # warning; composing parts onto such a URDF refused it ("not valid XML").
    text, warnings = compose(main, "arm.urdf", [part(tmp_path)], tmp_path / "main")
    assert next(w for w in warnings if warned in w).startswith("arm.urdf:")
    assert "hand_palm" in [link.get("name") for link in etree.fromstring(text).iter("link")]
