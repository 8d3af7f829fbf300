"""Same inputs, same bytes: builds in different folders, with different job counts, hash seeds
and caches of their own (so products are made twice, not read back from one shared cache)."""

from __future__ import annotations

import filecmp

import pytest

from mjcfbuild.errors import EXIT_OK
from tests.conftest import copy_example, run_cli


def output_files(folder):
    return sorted(
        p.relative_to(folder)
        for p in folder.rglob("*")
        # The report (build times, pictures) describes a build; the model files are the output.
        if p.is_file() and not {".mjcfbuild", "report"} & set(p.relative_to(folder).parts)
    )


def _build(example, tmp_path, name: str, jobs: str, seed: str, warm_manifest: bool):
    folder = copy_example(example, tmp_path / name)
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / f"cache-{name}"), "PYTHONHASHSEED": seed}
    if warm_manifest:  # the build then reads its validated manifest back from the cache
        assert run_cli("graph", cwd=folder, env=env).code == EXIT_OK
    result = run_cli("build", "-q", "--no-check", "-j", jobs, cwd=folder, env=env)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    return folder / "mjcf"


def _assert_identical(first, second):
    files = output_files(first)
    assert files == output_files(second)
    _, mismatch, errors = filecmp.cmpfiles(first, second, files, shallow=False)
    assert mismatch == [] and errors == []
    return files


def test_two_clean_builds_in_different_folders_are_byte_identical(tmp_path):
    first = _build("arm", tmp_path, "one", "2", "1", warm_manifest=False)
    second = _build("arm", tmp_path / "elsewhere", "two", "1", "2", warm_manifest=True)
    assert len(_assert_identical(first, second)) >= 7


def test_a_source_outside_the_manifest_folder_and_modify_attributes(tmp_path):
    """The native demo's xacro is in a sibling folder, and it sets attributes with `modify`."""
    first = _build("reference_demo_native", tmp_path, "one", "2", "1", warm_manifest=False)
    second = _build(
        "reference_demo_native", tmp_path / "elsewhere", "two", "1", "3", warm_manifest=True
    )
    for path in _assert_identical(first, second):
        assert str(tmp_path).encode() not in (first / path).read_bytes(), path


def test_outputs_hold_no_absolute_paths(tmp_path):
    mjcf = _build("arm", tmp_path, "one", "2", "0", warm_manifest=False)
    for path in output_files(mjcf):
        data = (mjcf / path).read_bytes()
        assert str(tmp_path).encode() not in data, path


@pytest.mark.slow
def test_reports_are_the_same_bytes_when_built_by_absolute_path_from_elsewhere(tmp_path):
    """The manifest named by its absolute path, from another current folder: the warning the
    native demo's inputs give (a joint equality replacing a <mimic>) names robot.yaml as it
    lies in its own folder, so the reports do not depend on where the build ran."""
    reports = []
    for name in ("one", "two"):
        folder = copy_example("reference_demo_native", tmp_path / name)
        env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / f"cache-{name}")}
        result = run_cli("build", "-q", str(folder / "robot.yaml"), cwd=tmp_path, env=env)
        assert result.code == EXIT_OK, result.stdout + result.stderr
        reports.append(folder / "mjcf")
    first, second = reports
    compared = ["report/report.md", "report/report.json", ".mjcfbuild/check.json"]
    _, mismatch, errors = filecmp.cmpfiles(first, second, compared, shallow=False)
    assert mismatch == [] and errors == []
    assert (
        "robot.yaml mujoco_inputs.raw:16: the joint equality"
        in (first / "report/report.md").read_text()
    )
    for path in first.rglob("*"):
        if path.is_file() and ".mjcfbuild" not in path.relative_to(first).parts:
            assert str(tmp_path).encode() not in path.read_bytes(), path
