"""Where mjcfbuild keeps what builds share, and a ``$MJCFBUILD_CACHE_DIR`` it cannot use."""

from __future__ import annotations

import os

import pytest

from mjcfbuild.cachedir import cache_dir_problem
from tests.conftest import run_cli


def test_a_cache_folder_that_can_be_made_is_no_problem(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "new" / "cache"))
    assert cache_dir_problem() is None and (tmp_path / "new" / "cache").is_dir()
    monkeypatch.delenv("MJCFBUILD_CACHE_DIR")
    assert cache_dir_problem() is None


def test_a_cache_folder_that_cannot_be_made_names_the_variable(monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", "/proc/mjcfbuild-cache")  # /proc makes none
    problem = cache_dir_problem()
    assert problem is not None
    assert problem.startswith("MJCFBUILD_CACHE_DIR=/proc/mjcfbuild-cache: cannot create it")
    assert "set it to a folder you can write" in problem


def test_a_read_only_cache_folder_names_the_variable(tmp_path, monkeypatch):
    if os.geteuid() == 0:
        pytest.skip("root may write in read-only folders")
    folder = tmp_path / "cache"
    folder.mkdir(mode=0o555)
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(folder))
    assert "it cannot be written" in (cache_dir_problem() or "")


def test_the_command_warns_once_and_goes_on(tmp_path):
    # Before: nothing said, and nothing was ever stored or found in the cache.
    result = run_cli(
        "cache", "show", cwd=tmp_path, env={"MJCFBUILD_CACHE_DIR": "/proc/mjcfbuild-cache"}
    )
    assert result.code == 0, result.stderr
    warnings = [line for line in result.stderr.splitlines() if "MJCFBUILD_CACHE_DIR" in line]
    assert len(warnings) == 1 and warnings[0].startswith("mjcfbuild: warning: "), result.stderr
    quiet = run_cli(
        "-q", "cache", "show", cwd=tmp_path, env={"MJCFBUILD_CACHE_DIR": "/proc/mjcfbuild-cache"}
    )
    assert quiet.stderr == ""
