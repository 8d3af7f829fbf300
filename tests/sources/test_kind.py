"""Telling xacro from URDF by what a file uses, and meshes from descriptions by content."""

from __future__ import annotations

from pathlib import Path

import pytest

from mjcfbuild.sources.kind import (
    mesh_kind,
    not_a_description,
    not_a_manifest,
    not_an_mjcf,
    xacro_evidence,
)

NS = '<robot name="r" xmlns:xacro="http://wiki.ros.org/xacro">\n'


def test_the_namespace_declaration_alone_is_no_evidence():
    assert xacro_evidence((NS + '<link name="a"/>\n</robot>\n').encode()) is None


def test_a_commented_out_xacro_element_is_no_evidence():
    data = NS + '<!-- <xacro:property name="x" value="1"/> -->\n<link name="a"/></robot>'
    assert xacro_evidence(data.encode()) is None


@pytest.mark.parametrize(
    ("body", "used"),
    [
        ('<xacro:leg side="l"/>', "<xacro:leg>"),  # any element xacro processes, macro calls too
        ('<link name="${prefix}base"/>', "${prefix}"),
        ("<link name='$(arg prefix)base'/>", "$(arg prefix)"),
    ],
)
def test_what_xacro_would_process_is_evidence_with_its_line(body, used):
    assert xacro_evidence((NS + '<link name="a"/>\n' + body + "\n</robot>").encode()) == (used, 3)


def test_a_dollar_outside_attributes_is_no_evidence():
    assert xacro_evidence(b'<robot name="r"><link name="a"/><!-- costs $5 --></robot>') is None


def test_meshes_are_told_by_content_whatever_their_name(tmp_path: Path):
    import struct

    binary = b"\0" * 80 + struct.pack("<I", 1) + b"\0" * 50
    assert mesh_kind(tmp_path / "robot.urdf", binary) == "an STL mesh"
    assert mesh_kind(tmp_path / "a.txt", b"solid x\nfacet normal 0 0 1\n") == "an STL mesh"
    assert mesh_kind(tmp_path / "a.txt", b"# x\nv 0 0 0\nv 1 0 0\nf 1 2 3\n") == "an OBJ mesh"
    assert mesh_kind(tmp_path / "a.xml", b"<?xml version='1.0'?><COLLADA/>") == (
        "a COLLADA (DAE) mesh"
    )
    assert mesh_kind(tmp_path / "a.bin", b"glTF\x02\0\0\0") == "a glTF (GLB) mesh"
    assert mesh_kind(tmp_path / "a", b"ply\nformat ascii 1.0\n") == "a PLY mesh"
    assert mesh_kind(tmp_path / "robot.urdf", (NS + "</robot>").encode()) is None


def test_other_files_are_named_for_what_they_are(tmp_path: Path):
    assert not_a_description(tmp_path / "m.sdf", b"<?xml version='1.0'?><sdf/>") == "an SDF model"
    assert not_a_description(tmp_path / "m.xml", b"<!-- x --><mujoco/>") == "an MJCF model"
    assert not_a_description(tmp_path / "r.urdf", b"  \n") == "an empty file"
    assert not_a_description(tmp_path / "r.urdf", b"name: robot\n") == "not XML"
    assert not_a_description(tmp_path / "r.urdf", b'<?xml version="1.0"?>\n<robot/>') is None


def test_binary_files_are_named_not_read_for_a_root_element(tmp_path: Path):
    # a PNG's compressed bytes hold a '<' followed by letters: no XML element
    png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR<JC>\0"
    assert not_a_description(tmp_path / "p.png", png) == "a PNG image"
    assert not_a_description(tmp_path / "r.urdf", b"%PDF-1.7\n<</Type>>") == "a PDF document"
    assert not_a_description(tmp_path / "r.urdf", b"\0\0<robot>") == "a binary file"


def test_what_is_plainly_no_manifest_is_named():
    robot = Path("robot.yaml")
    assert not_a_manifest(robot, b'<?xml version="1.0"?>\n<robot name="r"/>') == "a URDF"
    assert not_a_manifest(robot, NS.encode() + b"<xacro:arg name='a'/></robot>") == ("a xacro file")
    assert not_a_manifest(robot, b"solid a\nfacet normal 0 0 1\nendsolid a\n") == "an STL mesh"
    assert not_a_manifest(robot, b"\x89PNG\r\n\x1a\n\0") == "a PNG image"
    assert not_a_manifest(robot, b"name: r\xe9\n") is None  # Latin-1: its reader says where
    # YAML, even YAML that starts with a merge key, is for the manifest's reader to judge
    assert not_a_manifest(robot, b"name: r\nsource: {urdf: r.urdf}\n") is None
    assert not_a_manifest(robot, b"<<: *defaults\nname: r\n") is None


def test_an_mjcf_model_is_told_from_a_urdf_past_a_long_licence_comment():
    licence = b"<!-- " + b"licence text " * 500 + b"-->\n"  # 6.5 kB before the root
    model = Path("model.xml")
    assert not_an_mjcf(model, licence + b"<mujoco/>") is None
    assert not_an_mjcf(model, licence + b'<robot name="r"/>') == "a URDF"
    assert not_an_mjcf(model, b"no element here") is None  # MuJoCo's to judge
    assert not_an_mjcf(Path("m.stl"), b"solid a\nfacet normal 0 0 1\nendsolid a\n") == (
        "an STL mesh"
    )
