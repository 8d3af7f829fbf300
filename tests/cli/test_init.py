"""``mjcfbuild init`` writes a manifest that builds."""

from __future__ import annotations

from mjcfbuild.errors import EXIT_OK, EXIT_USAGE
from tests.conftest import EXAMPLES


def test_init_then_build(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    result = cli("init", str(source), "-o", "robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert "mjcfbuild build robot.yaml" in result.stdout
    built = cli("build", "-q", cwd=tmp_path)
    assert built.code == EXIT_OK, built.stderr
    assert (tmp_path / "mjcf" / "example_arm.xml").exists()


def test_init_does_not_overwrite_without_force(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    (tmp_path / "robot.yaml").write_text("mine")
    result = cli("init", str(source), cwd=tmp_path)
    assert result.code == EXIT_USAGE and (tmp_path / "robot.yaml").read_text() == "mine"
    assert cli("init", str(source), "--force", cwd=tmp_path).code == EXIT_OK


def test_packages_without_package_xml_are_inferred_from_the_uris(cli, tmp_path):
    """jvrc-, icub- and upkie-style wheels: the package folder is there, package.xml is not."""
    from tests.conftest import two_link_urdf, write
    from tests.meshes.samples import ascii_stl

    share = tmp_path / "share" / "jvrc_description"
    (share / "meshes").mkdir(parents=True)
    ascii_stl(share / "meshes" / "base.stl")
    urdf = two_link_urdf().replace(
        '<geometry><box size="0.2 0.2 0.1"/></geometry>',
        '<geometry><mesh filename="package://jvrc_description/meshes/base.stl"/></geometry>',
    )
    write(share / "urdf" / "jvrc1.urdf", urdf)
    work = tmp_path / "work"
    work.mkdir()
    result = cli("init", str(share / "urdf" / "jvrc1.urdf"), "-o", "robot.yaml", cwd=work)
    assert result.code == EXIT_OK, result.stderr
    text = (work / "robot.yaml").read_text()
    assert "packages: {}" not in text
    assert "  jvrc_description: ../share/jvrc_description\n" in text
    assert "# jvrc_description: inferred (no package.xml)" in text and "meshes/base.stl" in text
    built = cli("build", "-q", "--no-check", cwd=work)
    assert built.code == EXIT_OK, built.stderr


def test_init_writes_commented_actuators_and_home_sections(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    assert cli("init", str(source), "-o", "robot.yaml", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    assert "\nactuators:\n  default: position" in text
    assert "\nhome: {}\n" in text and '#   "*elbow*": 1.57' in text
    assert "# self_collision: {srdf: config/robot.srdf}" in text
    assert "free_joint: false" in text  # an arm: no leg words in its names


def _init_free_joint(cli, folder, urdf: str) -> tuple[bool, str]:
    from mjcfbuild.manifest.loading import load_manifest
    from tests.conftest import write

    write(folder / "robot.urdf", urdf)
    assert cli("init", "robot.urdf", "-o", "robot.yaml", cwd=folder).code == EXIT_OK
    text = (folder / "robot.yaml").read_text()
    return load_manifest(folder / "robot.yaml").options.free_joint, text


def test_init_finds_a_walker_by_its_legs_not_its_names(cli, tmp_path):
    """TALOS-like names (leg_left_1, ...) say nothing; four limbs reaching the floor below
    the root do."""
    from tests.control.robots import quadruped

    renamed = quadruped()
    for index, part in enumerate(("hip", "thigh", "calf")):
        renamed = renamed.replace(f"_{part}", f"_link_{index}")
    floating, text = _init_free_joint(cli, tmp_path, renamed)
    assert floating
    assert "4 limbs" in text and "reach" in text


def test_init_finds_a_wheeled_base_floats_and_an_arm_named_hip_does_not(cli, tmp_path):
    from tests.conftest import two_link_urdf
    from tests.control.robots import rover

    floating, text = _init_free_joint(cli, tmp_path / "rover", rover())
    assert floating and "left_wheel_joint" in text and "wheels" in text
    arm = two_link_urdf().replace('name="hinge"', 'name="hip_knee_joint"')
    assert _init_free_joint(cli, tmp_path / "arm", arm)[0] is False
