"""Same inputs, same bytes: builds in different folders, with different job counts."""

from __future__ import annotations

import filecmp

import mjcfbuild
from tests.conftest import copy_example


def output_files(folder):
    return sorted(
        p.relative_to(folder)
        for p in folder.rglob("*")
        # The report (build times, pictures) describes a build; the model files are the output.
        if p.is_file() and not {".mjcfbuild", "report"} & set(p.relative_to(folder).parts)
    )


def test_two_clean_builds_in_different_folders_are_byte_identical(tmp_path):
    first = copy_example("arm", tmp_path / "one")
    second = copy_example("arm", tmp_path / "elsewhere" / "two")
    mjcfbuild.build(first / "robot.yaml", jobs=2)
    mjcfbuild.build(second / "robot.yaml", jobs=1)
    files = output_files(first / "mjcf")
    assert files == output_files(second / "mjcf")
    assert len(files) >= 7
    _, mismatch, errors = filecmp.cmpfiles(first / "mjcf", second / "mjcf", files, shallow=False)
    assert mismatch == [] and errors == []


def test_outputs_hold_no_absolute_paths(tmp_path):
    arm = copy_example("arm", tmp_path)
    mjcfbuild.build(arm / "robot.yaml", jobs=2)
    for path in output_files(arm / "mjcf"):
        data = (arm / "mjcf" / path).read_bytes()
        assert str(tmp_path).encode() not in data, path
