"""Resolving the meshes and textures a URDF names, and naming the meshes."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.urdf.parse import parse_urdf
from mjcfbuild.urdf.resolve import resolve_files
from tests.conftest import write


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
