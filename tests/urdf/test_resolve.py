"""Resolving the meshes and textures a URDF names, and naming the meshes."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import EXIT_INPUT, InputError
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.urdf.parse import parse_urdf
from mjcfbuild.urdf.resolve import resolve_files
from tests.conftest import run_cli, simple_manifest, write


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


def test_unsupported_format(tmp_path):
    write(tmp_path / "a.3ds", "x")
    with pytest.raises(InputError, match="unsupported format"):
        resolve_files(robot_with("a.3ds"), tmp_path, PackageResolver({}, {}))


def test_unknown_package_points_at_the_urdf_line(tmp_path):
    with pytest.raises(InputError) as info:
        resolve_files(robot_with("package://nope/a.stl"), tmp_path, PackageResolver({}, {}))
    assert info.value.location.line == 2
    assert "unknown package 'nope'" in info.value.message


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
