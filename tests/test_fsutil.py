"""File-system helpers: finding the file a missing path names in another letter case."""

from __future__ import annotations

from mjcfbuild.fsutil import case_match, case_suggestion, unreadable_file
from tests.conftest import write


def test_a_file_spelt_in_another_letter_case_is_found(tmp_path):
    write(tmp_path / "meshes" / "part.stl", "x")
    asked = tmp_path / "Meshes" / "part.STL"
    match = case_match(asked)
    assert match == tmp_path / "meshes" / "part.stl"
    assert case_suggestion(asked, match) == "meshes/part.stl"
    assert unreadable_file(asked) == "not found; did you mean 'meshes/part.stl'?"


def test_a_name_that_differs_in_more_than_case_has_no_match(tmp_path):
    write(tmp_path / "part.stl", "x")
    assert case_match(tmp_path / "part.obj") is None
    assert case_match(tmp_path / "nowhere" / "part.stl") is None
    assert unreadable_file(tmp_path / "part.obj") == "not found"


def test_an_existing_path_is_no_match_of_itself(tmp_path):
    write(tmp_path / "part.stl", "x")
    assert case_match(tmp_path / "part.stl") is None


def test_of_several_spellings_the_first_in_order_is_named(tmp_path):
    write(tmp_path / "Part.stl", "x")
    write(tmp_path / "part.STL", "x")
    assert case_match(tmp_path / "PART.stl") == tmp_path / "Part.stl"
