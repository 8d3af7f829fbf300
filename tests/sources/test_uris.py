"""Resolving package://, file:// and relative file references."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.sources.uris import resolve_uri, uri_package_folder


@pytest.fixture
def resolver(tmp_path):
    (tmp_path / "pkg").mkdir()
    return PackageResolver({"pkg": tmp_path / "pkg"}, {})


def test_package_uri(tmp_path, resolver):
    assert resolve_uri("package://pkg/meshes/a%20b.stl", tmp_path, resolver) == (
        tmp_path / "pkg" / "meshes" / "a b.stl"
    )


def test_relative_paths_are_relative_to_the_urdf_folder(tmp_path, resolver):
    base = tmp_path / "pkg" / "urdf"
    assert resolve_uri("../meshes/a.stl", base, resolver) == tmp_path / "pkg" / "meshes" / "a.stl"


def test_file_uris_absolute_and_relative(tmp_path, resolver):
    assert resolve_uri(f"file://{tmp_path}/x.stl", tmp_path / "pkg", resolver) == tmp_path / "x.stl"
    assert resolve_uri("file://meshes/x.stl", tmp_path, resolver) == tmp_path / "meshes" / "x.stl"


def test_remote_and_empty_references_are_errors(tmp_path, resolver):
    with pytest.raises(InputError, match="does not download"):
        resolve_uri("https://example.com/a.stl", tmp_path, resolver)
    with pytest.raises(InputError, match="empty"):
        resolve_uri("  ", tmp_path, resolver)
    with pytest.raises(InputError, match="names no package"):
        resolve_uri("package://", tmp_path, resolver)


def test_a_package_uri_naming_no_file_in_its_package(tmp_path, resolver):
    # Genesis' fancy_wheel.urdf writes package://fancy_wheel.obj for the OBJ beside it (as
    # pybullet reads it); it was "unknown package 'fancy_wheel.obj'", to be added as a package.
    (tmp_path / "wheel.obj").write_text("v 0 0 0\n")
    with pytest.raises(InputError) as info:
        resolve_uri("package://wheel.obj", tmp_path, resolver)
    assert info.value.message == "'package://wheel.obj' names package 'wheel.obj' but no file in it"
    assert info.value.hint == "'wheel.obj' is a file beside the URDF: write filename=\"wheel.obj\""
    with pytest.raises(InputError) as info:
        resolve_uri("package://pkg/", tmp_path, resolver)
    assert info.value.message == "'package://pkg/' names package 'pkg' but no file in it"
    assert info.value.hint == "write package://pkg/<the file's path inside it>"
    # onshape-to-robot's package:///wheel.obj: the package part is empty, not 'wheel.obj'.
    with pytest.raises(InputError) as info:
        resolve_uri("package:///wheel.obj", tmp_path, resolver)
    assert info.value.message == "'package:///wheel.obj' names no package, only a file"
    assert info.value.hint == "'wheel.obj' is a file beside the URDF: write filename=\"wheel.obj\""


def test_package_uri_with_an_extra_slash(tmp_path, resolver):
    assert resolve_uri("package:///pkg/a.stl", tmp_path, resolver) == tmp_path / "pkg" / "a.stl"


def test_the_package_folder_a_uri_names(tmp_path, resolver):
    folder = tmp_path / "pkg"
    assert uri_package_folder("package://pkg/../../x.obj", resolver) == folder
    assert uri_package_folder(" model:///pkg/m.stl", resolver) == folder
    assert uri_package_folder("file:///pkg/m.stl", resolver) is None
    assert uri_package_folder("meshes/m.stl", resolver) is None
