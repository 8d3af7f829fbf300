"""``mjcfbuild init`` writes a manifest that builds."""

from __future__ import annotations

import re

import pytest

from mjcfbuild.errors import EXIT_INPUT, EXIT_OK, EXIT_USAGE
from tests.conftest import EXAMPLES


def test_init_then_build(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    result = cli("init", str(source), "-o", "robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert "mjcfbuild build robot.yaml" in result.stdout
    built = cli("build", "-q", cwd=tmp_path)
    assert built.code == EXIT_OK, built.stderr
    assert (tmp_path / "mjcf" / "example_arm.xml").exists()


@pytest.mark.parametrize(
    ("robot", "name"),
    [("SO_5DOF_ARM100_8j_URDF.SLDASM", "so100"), ("arm_v2", "arm_v2"), ("$(arg name)", "so100")],
)
def test_init_names_the_model_after_the_robot_not_a_cad_assembly(cli, tmp_path, robot, name):
    # mani-skill's so100.urdf names its robot after the SolidWorks assembly it was exported from
    from tests.conftest import two_link_urdf, write

    text = two_link_urdf()
    write(tmp_path / "so100.urdf", re.sub(r'<robot name="[^"]*"', f'<robot name="{robot}"', text))
    assert cli("init", "so100.urdf", cwd=tmp_path).code == EXIT_OK
    assert f"\nname: {name}\n" in (tmp_path / "robot.yaml").read_text()


def test_init_does_not_overwrite_without_force(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    (tmp_path / "robot.yaml").write_text("mine")
    result = cli("init", str(source), cwd=tmp_path)
    assert result.code == EXIT_USAGE and (tmp_path / "robot.yaml").read_text() == "mine"
    assert cli("init", str(source), "--force", cwd=tmp_path).code == EXIT_OK


def test_quiet_init_prints_nothing_but_errors(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    result = cli("-q", "init", str(source), cwd=tmp_path)
    assert result.code == EXIT_OK and (result.stdout, result.stderr) == ("", "")
    assert (tmp_path / "robot.yaml").is_file()
    again = cli("init", str(source), "-q", cwd=tmp_path)
    assert again.code == EXIT_USAGE and again.stderr.count("\n") == 1


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


# ---- the source kind, from what the file uses ------------------------------------------------


def test_a_urdf_that_only_declares_the_xacro_namespace_is_a_urdf(cli, tmp_path):
    """Read through xacro, its errors would cite lines of an expanded copy."""
    from tests.conftest import two_link_urdf, write

    declared = two_link_urdf().replace(
        '<robot name="two_link">', '<robot name="two_link" xmlns:xacro="http://wiki.ros.org/xacro">'
    )
    write(tmp_path / "robot.urdf.xacro", declared)
    assert cli("init", "robot.urdf.xacro", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    assert "  urdf: robot.urdf.xacro\n" in text and "args:" not in text
    built = cli("build", "-q", "--no-check", cwd=tmp_path)
    assert built.code == EXIT_OK, built.stderr


def test_a_substitution_without_xacro_elements_makes_a_xacro_source(cli, tmp_path):
    from tests.conftest import two_link_urdf, write

    substituted = two_link_urdf().replace(
        '<box size="0.2 0.2 0.1"/>', '<box size="${0.1*2} 0.2 0.1"/>'
    )
    assert "xacro:" not in substituted
    write(tmp_path / "robot.urdf", substituted)
    assert cli("init", "robot.urdf", cwd=tmp_path).code == EXIT_OK
    assert "  xacro: robot.urdf\n" in (tmp_path / "robot.yaml").read_text()
    built = cli("build", "-q", "--no-check", cwd=tmp_path)
    assert built.code == EXIT_OK, built.stderr


def test_the_build_refuses_a_urdf_source_that_uses_a_substitution(cli, tmp_path):
    """The same rule as init's: this URDF needs xacro, and says where."""
    from tests.conftest import two_link_urdf, write

    substituted = two_link_urdf().replace('<box size="0.2 0.2 0.1"/>', '<box size="${s} 0.2 0.1"/>')
    write(tmp_path / "robot.urdf", substituted)
    write(tmp_path / "robot.yaml", "name: robot\nsource:\n  urdf: robot.urdf\n")
    line = substituted[: substituted.index("${s}")].count("\n") + 1
    result = cli("build", "-q", cwd=tmp_path)
    assert result.code == EXIT_INPUT
    assert f"robot.urdf:{line}: this file is xacro (${{s}} at line {line}), not a URDF" in (
        result.stderr
    )


def _binary_stl(path):
    import struct

    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    path.write_bytes(b"\0" * 80 + struct.pack("<I", 1) + triangle)


def _ascii_stl(path):
    from tests.meshes.samples import ascii_stl

    ascii_stl(path)


def _obj(path):
    path.write_text("# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")


def _dae(path):
    path.write_text(
        '<?xml version="1.0"?>\n<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema"'
        ' version="1.4.1"/>\n'
    )


def _gltf(binary):
    def make(path):
        from tests.meshes.samples import gltf

        made = gltf(path.parent / "made", binary)
        path.write_bytes(made.read_bytes())

    return make


def _ply(path):
    from tests.meshes.samples import coloured_ply

    coloured_ply(path)


@pytest.mark.parametrize(
    ("name", "make", "what"),
    [
        ("robot.stl", _binary_stl, "an STL mesh"),
        ("robot.stl", _ascii_stl, "an STL mesh"),
        ("robot.urdf", _binary_stl, "an STL mesh"),  # by content, whatever its name
        ("robot.obj", _obj, "an OBJ mesh"),
        ("robot.dae", _dae, "a COLLADA (DAE) mesh"),
        ("robot.glb", _gltf(True), "a glTF (GLB) mesh"),
        ("robot.gltf", _gltf(False), "a glTF mesh"),
        ("robot.ply", _ply, "a PLY mesh"),
    ],
    ids=["binary-stl", "ascii-stl", "stl-named-urdf", "obj", "dae", "glb", "gltf", "ply"],
)
def test_init_refuses_a_mesh_saying_what_it_is(cli, tmp_path, name, make, what):
    make(tmp_path / name)
    result = cli("init", name, cwd=tmp_path)
    assert result.code == EXIT_INPUT
    errors = [line for line in result.stderr.splitlines() if line.strip()]
    assert errors == [
        f"mjcfbuild: error: {name} is {what}, not a URDF or xacro file (pass the robot's .urdf"
        " or .xacro file; it names its meshes itself)"
    ]
    assert not (tmp_path / "robot.yaml").exists()


def test_init_refuses_an_sdf_model(cli, tmp_path):
    (tmp_path / "model.sdf").write_text(
        '<?xml version="1.0"?>\n<sdf version="1.7"><model/></sdf>\n'
    )
    result = cli("init", "model.sdf", cwd=tmp_path)
    assert result.code == EXIT_INPUT
    assert "model.sdf is an SDF model, not a URDF or xacro file" in result.stderr


# ---- packages, from package.xml files ---------------------------------------------------------


def _described_package(root, folder: str, xml_name: str | None):
    """A package folder with a mesh and a URDF naming it as package://jvrc_description."""
    from tests.conftest import two_link_urdf, write
    from tests.meshes.samples import ascii_stl

    share = root / folder
    (share / "meshes").mkdir(parents=True)
    ascii_stl(share / "meshes" / "base.stl")
    if xml_name is not None:
        write(share / "package.xml", f"<package format='3'><name>{xml_name}</name></package>\n")
    urdf = two_link_urdf().replace(
        '<geometry><box size="0.2 0.2 0.1"/></geometry>',
        '<geometry><mesh filename="package://jvrc_description/meshes/base.stl"/></geometry>',
    )
    return write(share / "urdf" / "jvrc1.urdf", urdf)


def _packages_section(text: str) -> list[str]:
    lines = text[text.index("\npackages:") :].splitlines()[2:]
    return lines[: next(i for i, line in enumerate(lines) if not line.startswith("  "))]


def test_a_package_with_its_package_xml_is_not_called_inferred(cli, tmp_path):
    urdf = _described_package(tmp_path, "jvrc_description", "jvrc_description")
    result = cli("init", str(urdf), "-o", "robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    text = (tmp_path / "robot.yaml").read_text()
    assert _packages_section(text) == ["  jvrc_description: jvrc_description"]
    assert "inferred" not in text
    assert cli("build", "-q", "--no-check", cwd=tmp_path).code == EXIT_OK


def test_one_name_per_folder_when_package_xml_names_it_otherwise(cli, tmp_path):
    """The description says jvrc_description, the folder's package.xml jvrc1: the build needs
    the name the description uses, once."""
    urdf = _described_package(tmp_path, "jvrc_description", "jvrc1")
    assert cli("init", str(urdf), "-o", "robot.yaml", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    section = _packages_section(text)
    assert section[-1] == "  jvrc_description: jvrc_description"
    assert len([line for line in section if not line.lstrip().startswith("#")]) == 1
    assert "no package.xml" not in text and "its package.xml names it 'jvrc1'" in text
    assert cli("build", "-q", "--no-check", cwd=tmp_path).code == EXIT_OK


def test_a_sibling_package_is_found_by_its_package_xml(cli, tmp_path):
    """In a workspace, package://robot_meshes is the folder whose package.xml says so, whatever
    the folder is called."""
    from tests.conftest import two_link_urdf, write
    from tests.meshes.samples import ascii_stl

    src = tmp_path / "src"
    (src / "meshes_pkg" / "stl").mkdir(parents=True)
    ascii_stl(src / "meshes_pkg" / "stl" / "base.stl")
    write(src / "meshes_pkg" / "package.xml", "<package><name>robot_meshes</name></package>\n")
    write(
        src / "robot_description" / "package.xml",
        "<package><name>robot_description</name></package>",
    )
    urdf = two_link_urdf().replace(
        '<geometry><box size="0.2 0.2 0.1"/></geometry>',
        '<geometry><mesh filename="package://robot_meshes/stl/base.stl"/></geometry>',
    )
    write(src / "robot_description" / "urdf" / "robot.urdf", urdf)
    source = src / "robot_description" / "urdf" / "robot.urdf"
    assert cli("init", str(source), "-o", "robot.yaml", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    assert _packages_section(text) == [
        "  robot_description: src/robot_description",
        "  robot_meshes: src/meshes_pkg",
    ]
    assert "inferred" not in text
    assert cli("build", "-q", "--no-check", cwd=tmp_path).code == EXIT_OK


def test_meshes_outside_every_package_set_read_outside_and_init_says_so(cli, tmp_path):
    """A URDF in its package reading '../../elsewhere/base.stl' beside the package: init wrote
    a manifest whose first build warned of the mesh; now it sets source.read_outside."""
    from tests.conftest import two_link_urdf, write
    from tests.meshes.samples import ascii_stl

    package = tmp_path / "ws" / "arm_pkg"
    write(package / "package.xml", "<package format='3'><name>arm_pkg</name></package>\n")
    (tmp_path / "ws" / "elsewhere").mkdir()
    ascii_stl(tmp_path / "ws" / "elsewhere" / "base.stl")
    urdf = two_link_urdf().replace(
        '<box size="0.2 0.2 0.1"/>', '<mesh filename="../../elsewhere/base.stl"/>'
    )
    write(package / "urdf" / "arm.urdf", urdf)
    line = next(n for n, text in enumerate(urdf.splitlines(), 1) if "elsewhere" in text)
    result = cli("init", "ws/arm_pkg/urdf/arm.urdf", "-o", "ws/arm_pkg/robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_OK and result.stderr == ""
    assert result.stdout.splitlines()[0] == (
        f"mjcfbuild: ws/arm_pkg/urdf/arm.urdf:{line}: reads '../../elsewhere/base.stl' from "
        "outside every package folder and robot.yaml's folder; robot.yaml sets "
        "source.read_outside: true, so the build reads it without a warning (to publish a "
        "self-contained model, move it into the description and drop that line)"
    )
    text = (package / "robot.yaml").read_text()
    assert "\n  read_outside: true\n" in text
    built = cli("build", "--no-check", "ws/arm_pkg/robot.yaml", cwd=tmp_path)
    assert built.code == EXIT_OK and "warning" not in built.stderr, built.stderr
    # Inside its package, the same mesh sets nothing.
    (package / "meshes").mkdir()
    ascii_stl(package / "meshes" / "base.stl")
    write(package / "urdf" / "arm.urdf", urdf.replace("../../elsewhere/", "../meshes/"))
    again = cli(
        "init", "--force", "ws/arm_pkg/urdf/arm.urdf", "-o", "ws/arm_pkg/robot.yaml", cwd=tmp_path
    )
    assert again.code == EXIT_OK and "read_outside" not in (package / "robot.yaml").read_text()
    assert again.stdout.count("\n") == 1


def test_a_package_two_package_xml_files_name_takes_the_nearest_and_says_so(cli, tmp_path):
    """Two folders of one workspace claim robot_meshes (catkin and colcon refuse to build
    such a workspace): the manifest takes the nearest, and both init and the manifest say
    which other folder claims it."""
    from tests.conftest import two_link_urdf, write
    from tests.meshes.samples import ascii_stl

    src = tmp_path / "src"
    for folder in ("meshes_pkg", "old_meshes"):
        (src / folder / "stl").mkdir(parents=True)
        ascii_stl(src / folder / "stl" / "base.stl")
        write(src / folder / "package.xml", "<package><name>robot_meshes</name></package>\n")
    urdf = two_link_urdf().replace(
        '<geometry><box size="0.2 0.2 0.1"/></geometry>',
        '<geometry><mesh filename="package://robot_meshes/stl/base.stl"/></geometry>',
    )
    write(src / "robot_description" / "urdf" / "robot.urdf", urdf)
    source = src / "robot_description" / "urdf" / "robot.urdf"
    result = cli("init", str(source), "-o", "robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    assert _packages_section(text) == [
        "  # robot_meshes: the nearest package.xml naming it; named by another in: src/old_meshes",
        "  robot_meshes: src/meshes_pkg",
    ]
    assert (
        "mjcfbuild: warning: src/old_meshes/package.xml: package 'robot_meshes' is named by 2 "
        "package.xml files; the manifest takes the nearest, src/meshes_pkg (catkin and colcon "
        "refuse a workspace with two): check its line under packages"
    ) in result.stderr
    assert cli("build", "-q", "--no-check", cwd=tmp_path).code == EXIT_OK


def test_init_says_what_the_first_build_will_stop_at(cli, tmp_path):
    # gaikpy's NICO (a lower limit above the upper) and pib-sdk's pib (meshes in a package the
    # wheel lacks): init wrote the manifest and said nothing; the build then stopped.
    from tests.conftest import two_link_urdf, write

    urdf = two_link_urdf().replace('lower="-1.5" upper="1.5"', 'lower="0.3" upper="-1.5"')
    urdf = urdf.replace(
        '<box size="0.2 0.2 0.1"/>', '<mesh filename="package://robot_meshes/base.stl"/>'
    )
    write(tmp_path / "robot.urdf", urdf)
    result = cli("init", "robot.urdf", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    line = next(n for n, text in enumerate(urdf.splitlines(), 1) if "<limit" in text)
    uri = next(n for n, text in enumerate(urdf.splitlines(), 1) if "package://" in text)
    assert result.stderr.splitlines() == [
        f"mjcfbuild: warning: robot.urdf:{uri}: package 'robot_meshes' not found; the "
        "manifest lists it commented out under packages: give it its folder (or pass "
        "--package NAME=DIR)",
        f"mjcfbuild: warning: robot.urdf:{line}: joint 'hinge' has lower limit "
        "0.3 above its upper limit -1.5 (swap them; if they mean 'no limit' (as pybullet reads "
        "them), make a revolute joint continuous, or give a prismatic one the range it can "
        "travel); the build stops there until the description is fixed",
    ]
    assert "#   robot_meshes: path/to/robot_meshes" in (tmp_path / "robot.yaml").read_text()
    built = cli("build", "--no-check", cwd=tmp_path)
    assert built.code == EXIT_INPUT  # where init said
    assert f"robot.urdf:{line}: joint 'hinge' has lower limit 0.3 above" in built.stderr


def test_init_says_a_missing_mesh_or_a_robot_without_mass_stops_the_first_build(cli, tmp_path):
    # dart's missing_mesh.urdf and joint_properties.urdf: init wrote the manifest and said
    # nothing; the first build then stopped.
    from tests.conftest import two_link_urdf, write

    urdf = two_link_urdf().replace('<box size="0.2 0.2 0.1"/>', '<mesh filename="gone.stl"/>')
    write(tmp_path / "robot.urdf", urdf)
    result = cli("init", "robot.urdf", cwd=tmp_path)
    line = next(n for n, text in enumerate(urdf.splitlines(), 1) if "gone.stl" in text)
    assert result.code == EXIT_OK, result.stderr
    assert result.stderr.startswith(f"mjcfbuild: warning: robot.urdf:{line}: file 'gone.stl'")
    assert result.stderr.rstrip().endswith("the build stops there until the description is fixed")
    massless = re.sub(r"<inertial>.*?</inertial>", "", two_link_urdf(), flags=re.DOTALL)
    write(tmp_path / "massless.urdf", massless)
    result = cli("init", "-o", "massless.yaml", "massless.urdf", cwd=tmp_path)
    assert "massless.urdf: no link of the robot has a mass (<inertial>)" in result.stderr
    assert (
        "or set inertia: {missing: geometry} in robot.yaml to give each link the mass of its "
        "geometry, as MuJoCo's own URDF import does)"
    ) in result.stderr


def test_init_names_an_included_file_that_fails_from_the_current_folder(cli, tmp_path):
    """A failure in a file the description includes is named as the build names it, from
    the folder init runs in, not by its absolute path."""
    from tests.conftest import write

    write(tmp_path / "desc" / "package.xml", "<package><name>desc</name></package>\n")
    write(
        tmp_path / "desc" / "urdf" / "r.urdf.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:include filename="$(find desc)/urdf/part.xacro"/>\n<link name="a"/>\n</robot>\n',
    )
    write(
        tmp_path / "desc" / "urdf" / "part.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<link name="${undefined_thing}"/>\n</robot>\n',
    )
    result = cli("init", "urdf/r.urdf.xacro", cwd=tmp_path / "desc")
    assert result.code == EXIT_OK, result.stderr
    assert result.stderr.startswith(
        "mjcfbuild: warning: urdf/part.xacro:2: xacro failed: name 'undefined_thing' is not defined"
    ), result.stderr
    built = cli("build", "--no-check", cwd=tmp_path / "desc")
    assert built.code == EXIT_INPUT and "error: urdf/part.xacro:2: xacro failed" in built.stderr


def test_init_takes_no_package_a_comment_mentions(cli, tmp_path):
    from tests.conftest import two_link_urdf, write

    old = '<!-- <mesh filename="package://old_meshes/base.stl"/> -->\n'
    write(tmp_path / "robot.urdf", two_link_urdf().replace("<link", old + "<link", 1))
    result = cli("init", "robot.urdf", cwd=tmp_path)
    assert result.code == EXIT_OK and result.stderr == "", result.stderr
    assert "old_meshes" not in (tmp_path / "robot.yaml").read_text()


def test_a_xacro_stopped_by_a_missing_package_is_warned_about_once(cli, tmp_path):
    from tests.conftest import write

    write(
        tmp_path / "robot.urdf.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find ghost_description)/urdf/parts.xacro"/>\n'
        '  <link name="base"><visual><geometry>\n'
        '    <mesh filename="package://ghost_description/meshes/base.stl"/>\n'
        "  </geometry></visual></link>\n</robot>\n",
    )
    result = cli("init", "robot.urdf.xacro", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert result.stderr.splitlines() == [
        "mjcfbuild: warning: robot.urdf.xacro:2: package 'ghost_description' not found; the "
        "manifest lists it commented out under packages: give it its folder (or pass "
        "--package NAME=DIR)"
    ]


def test_init_of_a_readable_description_warns_of_nothing(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    result = cli("init", str(source), cwd=tmp_path)
    assert result.code == EXIT_OK and result.stderr == ""


def test_init_does_not_warn_of_a_package_the_ros_environment_holds(cli, tmp_path):
    from tests.conftest import two_link_urdf, write

    box = '<box size="0.2 0.2 0.1"/>'
    mesh = '<mesh filename="package://robot_meshes/base.stl"/>'
    write(tmp_path / "robot.urdf", two_link_urdf().replace(box, mesh))
    write(
        tmp_path / "ros" / "robot_meshes" / "package.xml",
        "<package><name>robot_meshes</name></package>",
    )
    write(tmp_path / "ros" / "robot_meshes" / "base.stl", "solid a\nendsolid a\n")
    result = cli(
        "init", "robot.urdf", cwd=tmp_path, env={"ROS_PACKAGE_PATH": str(tmp_path / "ros")}
    )
    assert result.code == EXIT_OK and result.stderr == ""


def test_a_folder_the_description_names_twice_says_both_names_are_it(cli, tmp_path):
    from tests.conftest import write
    from tests.meshes.samples import ascii_stl

    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    ascii_stl(tmp_path / "pkg" / "meshes" / "base.stl")
    write(tmp_path / "pkg" / "package.xml", "<package><name>pkg_a</name></package>")
    write(
        tmp_path / "pkg" / "urdf" / "r.urdf",
        '<robot name="r"><link name="a"><visual><geometry><mesh '
        'filename="package://pkg_a/meshes/base.stl"/></geometry></visual></link>'
        '<link name="b"><visual><geometry><mesh filename="package://pkg_b/meshes/base.stl"/>'
        '</geometry></visual></link><joint name="j" type="fixed"><parent link="a"/>'
        '<child link="b"/></joint></robot>',
    )
    assert cli("init", "pkg/urdf/r.urdf", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    assert "  pkg_a: pkg\n" in text and "  pkg_b: pkg\n" in text
    assert "names it 'pkg_a', which the description uses too: both names are this folder" in text
    assert "does not use" not in text


def test_a_package_xml_beside_none_of_the_files_does_not_take_the_name(cli, tmp_path):
    """hpp-environments' wheel: share/hpp-environments/package.xml names the package, its
    meshes sit in share/hpp_environments; the build then stopped at the first mesh."""
    from tests.conftest import write

    urdf = _described_package(tmp_path / "share", "jvrc_description", None)
    write(
        tmp_path / "share" / "jvrc-description" / "package.xml",
        "<package format='3'><name>jvrc_description</name></package>\n",
    )
    assert cli("init", str(urdf), "-o", "robot.yaml", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    assert _packages_section(text)[-1] == "  jvrc_description: share/jvrc_description"
    assert "holds none of the files the description names in it" in text
    assert cli("build", "-q", "--no-check", cwd=tmp_path).code == EXIT_OK


# ---- xacro arguments --------------------------------------------------------------------------

ARGS_XACRO = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">
  <xacro:arg name="robot_name" default = "px100"/>
  <xacro:arg name='prefix' default='left_'/>
  <xacro:arg default="0.3" name="length"/>
  <xacro:arg name="with_gazebo" default="false"/>
  <xacro:if value="$(arg with_gazebo)">
    <xacro:include filename="$(find arm_gazebo)/urdf/arm.gazebo"/>
  </xacro:if>
  <link name="$(arg prefix)base"/>
</robot>
"""


def test_init_lists_every_declared_argument_as_xacro_reads_it(cli, tmp_path):
    """Spaces around '=', single quotes and default before name: xacro reads all three; init
    listed one of them, with an empty default."""
    from tests.conftest import write

    write(tmp_path / "arm.urdf.xacro", ARGS_XACRO)
    assert cli("init", "arm.urdf.xacro", "-o", "robot.yaml", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    for line in ('#   robot_name: "px100"', '#   prefix: "left_"', "#   length: 0.3"):
        assert line in text, text


def test_a_package_only_a_false_condition_names_is_not_called_needed(cli, tmp_path):
    """$(find arm_gazebo) under <xacro:if> of an argument false by default (every Interbotix
    xsarm xacro): xacro and the build do without it, and init warned that it was missing."""
    from tests.conftest import write

    write(tmp_path / "arm.urdf.xacro", ARGS_XACRO)
    result = cli("init", "arm.urdf.xacro", "-o", "robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_OK and "arm_gazebo" not in result.stderr, result.stderr
    text = (tmp_path / "robot.yaml").read_text()
    assert "#   arm_gazebo: path/to/arm_gazebo  # only with other xacro arguments" in text


def test_a_package_found_in_ros_package_path_and_used_stays_needed(cli, tmp_path):
    """An always-taken include through $(find inc_pkg), found in ROS_PACKAGE_PATH, leaves no
    package:// in the URDF; it is used all the same, not "only with other arguments"."""
    from tests.conftest import write

    write(tmp_path / "ws" / "inc_pkg" / "package.xml", "<package><name>inc_pkg</name></package>\n")
    write(
        tmp_path / "ws" / "inc_pkg" / "part.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/></robot>\n',
    )
    write(
        tmp_path / "desc" / "robot.urdf.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
        '  <xacro:include filename="$(find inc_pkg)/part.xacro"/>\n</robot>\n',
    )
    env = {"ROS_PACKAGE_PATH": str(tmp_path / "ws")}
    result = cli("init", "robot.urdf.xacro", "-o", "robot.yaml", cwd=tmp_path / "desc", env=env)
    assert result.code == EXIT_OK, result.stderr
    text = (tmp_path / "desc" / "robot.yaml").read_text()
    assert "#   inc_pkg: path/to/inc_pkg  # needed by the description" in text, text


def test_an_argument_read_before_its_declaration_is_given_its_default(cli, tmp_path):
    """ur_description's <robot name="$(arg name)"> comes before <xacro:arg name="name"
    default="ur"/>: xacro reads in order, so the default never applies there. init wrote
    args: {} and the first build failed; the build's hint said to give a default it has."""
    from tests.conftest import INERTIA, write

    write(
        tmp_path / "r.urdf.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="$(arg name)">\n'
        # a macro's body is read where it is called, after the declaration
        '  <xacro:macro name="m"><link name="$(arg other)x"/></xacro:macro>\n'
        '  <xacro:arg name="name" default="ur"/>\n  <xacro:arg name="other" default="1"/>\n'
        f'  <link name="base">{INERTIA}</link>\n  <xacro:m/>\n'
        '  <joint name="j" type="fixed"><parent link="base"/><child link="1x"/></joint>\n'
        "</robot>\n",
    )
    assert cli("init", "r.urdf.xacro", cwd=tmp_path).code == EXIT_OK
    text = (tmp_path / "robot.yaml").read_text()
    assert '  args:\n    name: "ur"\n' in text and "    other:" not in text
    assert cli("build", "--no-check", cwd=tmp_path).code == EXIT_OK
    (tmp_path / "robot.yaml").write_text(text.replace('  args:\n    name: "ur"\n', "  args: {}\n"))
    failed = cli("build", "--no-check", cwd=tmp_path)
    assert "its <xacro:arg> (line 3) comes after this use" in failed.stderr


DUPLICATE_XACRO = """<?xml version="1.0"?>
<robot name="dup" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="extra" default="true"/>
  <link name="base"/>
<xacro:if value="$(arg extra)">
  <link name="plate"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="plate"/></joint>
</xacro:if>
  <link name="plate"/>
</robot>
"""


def test_a_name_defined_twice_names_both_xacro_lines_in_init_build_and_check(cli, tmp_path):
    """init named the expanded line of both (line 23 of a 16-line file), build the expanded
    line of the first ("xacro:13 ... first at line 13")."""
    from tests.conftest import write

    write(tmp_path / "robot.urdf.xacro", DUPLICATE_XACRO)
    write(tmp_path / "m.xml", "<mujoco><worldbody/></mujoco>\n")
    said = "robot.urdf.xacro:9: link 'plate' is defined twice (first at line 6)"
    init = cli("init", "robot.urdf.xacro", "-o", "robot.yaml", cwd=tmp_path)
    assert said in init.stderr, init.stderr
    build = cli("build", "--no-check", cwd=tmp_path)
    assert build.code == 4 and said + " [expanded: mjcf/.mjcfbuild/source.urdf:" in build.stderr
    check = cli("check", "--urdf", "robot.urdf.xacro", "--mjcf", "m.xml", cwd=tmp_path)
    assert said + " [line " in check.stderr, check.stderr
