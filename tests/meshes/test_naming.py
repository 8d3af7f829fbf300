"""Mesh names: short, unique without regard to case, independent of where the robot lives."""

from __future__ import annotations

from mjcfbuild.meshes.naming import assign_mesh_ids, sanitise


def test_stems_when_unique():
    ids = assign_mesh_ids(["/w/pkg/meshes/base.stl", "/w/pkg/meshes/arm link.dae"])
    assert ids == {"/w/pkg/meshes/base.stl": "base", "/w/pkg/meshes/arm link.dae": "arm_link"}


def test_same_stem_takes_the_folder_that_differs():
    ids = assign_mesh_ids(["/w/pkg/meshes/visual/link0.dae", "/w/pkg/meshes/collision/link0.stl"])
    assert sorted(ids.values()) == ["collision_link0", "visual_link0"]


def test_names_do_not_depend_on_where_the_robot_is():
    here = assign_mesh_ids(["/home/a/ws/pkg/v/x.stl", "/home/a/ws/pkg/c/x.stl"])
    there = assign_mesh_ids(["/tmp/ci/build/pkg/v/x.stl", "/tmp/ci/build/pkg/c/x.stl"])
    assert sorted(here.values()) == sorted(there.values()) == ["c_x", "v_x"]


def test_case_only_differences_are_numbered():
    ids = assign_mesh_ids(["/p/Link.STL", "/p/link.stl"])
    assert sorted(ids.values(), key=str.lower) == ["Link", "link_2"]
    assert len({v.lower() for v in ids.values()}) == 2


def test_sanitise():
    assert sanitise("a b.c/d") == "a_b_c_d"
    assert sanitise("...") == "mesh"
