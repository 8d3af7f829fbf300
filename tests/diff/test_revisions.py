"""Git revisions resolved and extracted into scratch folders, with real git."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

from mjcfbuild import filesig
from mjcfbuild.diff import revisions
from mjcfbuild.errors import InputError, UsageError
from mjcfbuild.fsutil import md5_file
from mjcfbuild.graph.hashes import HashCache
from tests.conftest import file_clock_past


def git(repo: Path, *args: str) -> str:
    command = ["git", "-c", "user.email=t@example.com", "-c", "user.name=t", *args]
    return subprocess.run(command, cwd=repo, check=True, capture_output=True, text=True).stdout


@pytest.fixture
def repo(tmp_path: Path) -> Path:
    """A repo with robot/robot.yaml in two commits (the second removes robot/old.txt)."""
    top = tmp_path / "repo"
    (top / "robot").mkdir(parents=True)
    (top / "robot" / "robot.yaml").write_text("name: one\n")
    (top / "robot" / "old.txt").write_text("old\n")
    git(top, "init", "-q", "-b", "main")
    git(top, "add", ".")
    git(top, "commit", "-qm", "one")
    (top / "robot" / "robot.yaml").write_text("name: two\n")
    git(top, "rm", "-q", "robot/old.txt")
    git(top, "commit", "-qam", "two")
    return top


def test_repository_finds_the_manifest_inside_the_work_tree(repo):
    found = revisions.repository(repo / "robot" / "robot.yaml")
    assert found.top == repo.resolve() and found.manifest == Path("robot/robot.yaml")


def test_resolve_names_the_commit_and_refuses_what_is_not_one(repo):
    found = revisions.repository(repo / "robot" / "robot.yaml")
    head = git(repo, "rev-parse", "HEAD").strip()
    assert revisions.resolve(found, "main").commit == head
    assert revisions.resolve(found, "main").label == f"main ({head[:10]})"
    for bad in ("nope", "--output=x", "main~5"):
        with pytest.raises(UsageError):
            revisions.resolve(found, bad)


def test_extract_follows_the_revision_and_keeps_an_unchanged_one(repo, tmp_path):
    found = revisions.repository(repo / "robot" / "robot.yaml")
    side = tmp_path / "side"
    first = revisions.extract(found, revisions.resolve(found, "main~1"), side)
    assert first.read_text() == "name: one\n" and (side / "src/robot/old.txt").is_file()
    marker = side / "src" / "built-here"
    marker.write_text("")
    revisions.extract(found, revisions.resolve(found, "main~1"), side)
    assert marker.is_file()  # the same commit: not extracted again
    second = revisions.extract(found, revisions.resolve(found, "main"), side)
    assert second.read_text() == "name: two\n"
    assert not (side / "src/robot/old.txt").exists() and not marker.exists()


def test_a_manifest_missing_at_the_revision_is_an_input_error(repo, tmp_path):
    (repo / "robot" / "new.yaml").write_text("name: new\n")
    git(repo, "add", ".")
    git(repo, "commit", "-qm", "new")
    found = revisions.repository(repo / "robot" / "new.yaml")
    with pytest.raises(InputError, match="does not exist at main~1"):
        revisions.extract(found, revisions.resolve(found, "main~1"), tmp_path / "side")


def test_a_revision_from_the_same_second_is_never_taken_for_the_one_it_replaces(
    tmp_path, monkeypatch
):
    """``git archive`` gives every file its commit's second: two commits made in one second
    (a script, a rebase) extract to files of the same size and time, often on the same inodes;
    the build's hash cache still reads the new revision's bytes."""
    monkeypatch.setattr(filesig, "RACY_NS", 0)  # hashes remembered at once, as after a build
    for variable in ("GIT_AUTHOR_DATE", "GIT_COMMITTER_DATE"):
        monkeypatch.setenv(variable, "2026-01-01T00:00:00Z")
    top = tmp_path / "repo"
    (top / "robot").mkdir(parents=True)
    (top / "robot" / "robot.yaml").write_text("mass: 1.5\n")
    git(top, "init", "-q", "-b", "main")
    git(top, "add", ".")
    git(top, "commit", "-qm", "one")
    (top / "robot" / "robot.yaml").write_text("mass: 2.5\n")
    git(top, "commit", "-qam", "two")
    found = revisions.repository(top / "robot" / "robot.yaml")
    side = tmp_path / "side"
    first = revisions.extract(found, revisions.resolve(found, "main~1"), side)
    cache = HashCache(None)
    old = cache.md5(first)
    before = os.stat(first)
    file_clock_past(tmp_path, before.st_ctime_ns)
    second = revisions.extract(found, revisions.resolve(found, "main"), side)
    after = os.stat(second)
    assert second == first and second.read_text() == "mass: 2.5\n"
    assert (after.st_size, after.st_mtime_ns) == (before.st_size, before.st_mtime_ns)
    assert cache.md5(second) == md5_file(second) != old
