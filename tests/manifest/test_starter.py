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


def test_a_robot_without_mass_is_not_floated_and_init_says_why(tmp_path):
    """A prop of one link and no <inertial> (a table): its base would float (nothing in it
    moves), but a floating base without mass cannot be simulated; the build then refused a
    description that has no moving body at all."""
    import mjcfbuild

    urdf = write(
        tmp_path / "prop.urdf",
        '<robot name="prop"><link name="table"><collision><geometry>'
        '<box size="1 0.6 0.05"/></geometry></collision></link></robot>',
    )
    warnings: list[str] = []
    notes: list[str] = []
    text = starter_manifest_text(
        urdf, {}, tmp_path, warnings=warnings, label="prop.urdf", notes=notes
    )
    assert parse_manifest(text).options.free_joint is False
    assert "# No link has a mass (<inertial>), and MuJoCo cannot simulate a floating" in text
    # A note of what init chose, not a warning of what the first build would stop at.
    assert warnings == []
    assert notes == [
        "prop.urdf: no link has a mass (<inertial>), so the manifest fixes the robot to the "
        "world (free_joint: false): MuJoCo cannot simulate a floating base without one (add "
        "the links' <inertial> elements, or set inertia: {missing: geometry} in robot.yaml to "
        "give each link the mass of its geometry, as MuJoCo's own URDF import does, then set "
        "free_joint: true to float it)"
    ]
    assert "(or masses from their geometry: inertia: {missing: geometry})" in text
    write(tmp_path / "robot.yaml", text)
    assert mjcfbuild.build(tmp_path / "robot.yaml", jobs=1).ok
    # With a mass, the same prop floats as before.
    heavy = urdf.read_text().replace(
        "<collision>",
        '<inertial><mass value="10"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" '
        'iyz="0"/></inertial><collision>',
    )
    write(urdf, heavy)
    warnings = []
    text = starter_manifest_text(urdf, {}, tmp_path, warnings=warnings, label="prop.urdf")
    assert parse_manifest(text).options.free_joint is True and warnings == []


def test_a_package_holding_robot_yaml_deep_inside_is_named_relative(tmp_path):
    """xacro's sdist keeps its PR2 in test/robots/pr2 and names files by $(find xacro): init
    run there wrote the package as an absolute path (three folders up), which breaks when the
    folder moves. A package holding robot.yaml moves with it."""
    import mjcfbuild
    from tests.conftest import two_link_urdf

    package = tmp_path / "moved" / "demo_pkg-1.0"
    write(package / "package.xml", "<package format='2'><name>demo_pkg</name></package>\n")
    robot = package / "test" / "robots" / "bot"
    urdf = two_link_urdf().split("<robot", 1)[1].split(">", 1)[1].rsplit("</robot>", 1)[0]
    write(robot / "links.xacro", f'<robot xmlns:xacro="http://wiki.ros.org/xacro">{urdf}</robot>')
    source = write(
        robot / "bot.urdf.xacro",
        '<robot name="bot" xmlns:xacro="http://wiki.ros.org/xacro">\n'
        '  <xacro:include filename="$(find demo_pkg)/test/robots/bot/links.xacro"/>\n</robot>\n',
    )
    text = starter_manifest_text(source, {}, robot)
    assert parse_manifest(text).packages == {"demo_pkg": "../../.."}
    assert "inferred" not in text  # found from its package.xml
    write(robot / "robot.yaml", text)
    (tmp_path / "moved").rename(tmp_path / "elsewhere")
    assert mjcfbuild.build(
        tmp_path / "elsewhere" / "demo_pkg-1.0" / robot.relative_to(package) / "robot.yaml",
        jobs=1,
        check=False,
    ).ok
