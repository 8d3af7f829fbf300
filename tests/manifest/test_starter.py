"""``mjcfbuild init``'s starting manifest is valid and mentions what the description needs."""

from __future__ import annotations

from mjcfbuild.manifest import parse_manifest
from mjcfbuild.manifest.starter import starter_manifest_text
from tests.conftest import EXAMPLES, write


def test_starter_for_xacro_lists_args_and_packages(tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    text = starter_manifest_text(source, {}, tmp_path)
    manifest = parse_manifest(text)
    assert manifest.name == "example_arm"
    assert manifest.source.xacro.endswith("arm.urdf.xacro")
    assert "#   with_camera: true" in text
    # the enclosing ROS package is found through its package.xml
    assert "arm_description" in manifest.packages


def test_starter_for_urdf_mentions_unresolved_packages(tmp_path):
    urdf = write(
        tmp_path / "r.urdf",
        '<robot name="dog"><link name="a"><visual><geometry>'
        '<mesh filename="package://dog_meshes/a.stl"/></geometry></visual></link></robot>',
    )
    text = starter_manifest_text(urdf, {}, tmp_path)
    manifest = parse_manifest(text)
    assert manifest.source.urdf == "r.urdf"
    assert "#   dog_meshes: path/to/dog_meshes" in text


def test_starter_shows_motors_as_a_commented_example(tmp_path):
    import yaml

    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    text = starter_manifest_text(source, {}, tmp_path)
    assert "# motors:" in text and "motor: go1_knee" in text
    # Uncommented, the example is a valid manifest section.
    block = [
        line[2:]
        for line in text.splitlines()
        if line.startswith("# motors:")
        or (
            line.startswith("#   ") and ("files:" in line or "define:" in line or "my_knee" in line)
        )
    ]
    settings = yaml.safe_load("\n".join(block))
    manifest = parse_manifest(text + "\n" + yaml.safe_dump(settings))
    assert "my_knee" in manifest.motors.define
