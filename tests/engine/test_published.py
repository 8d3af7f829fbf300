"""What a build publishes, whether it changed, and what git does not track yet (real git)."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from mjcfbuild.engine.published import changes, git_holds, git_status, snapshot


def _git(*args: str, cwd) -> None:
    subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@t", *args],
        cwd=cwd,
        check=True,
        capture_output=True,
    )


def _repo_with_a_conflict(top: Path, files: list[Path], conflicted: Path) -> None:
    """A repository at ``top`` with ``files`` committed as a build wrote them, and a merge
    that left ``conflicted`` (one of them) in conflict."""
    _git("init", "-q", "-b", "main", cwd=top)
    for path in files:
        path.write_text("built\n")
    _git("add", "-A", cwd=top)
    _git("commit", "-qm", "built", cwd=top)
    for branch, text in (("other", "other\n"), ("main", "main\n")):
        _git("checkout", "-q", *(["-b"] if branch == "other" else []), branch, cwd=top)
        conflicted.write_text(text)
        _git("commit", "-qam", branch, cwd=top)
    merge = subprocess.run(["git", "merge", "-q", "other"], cwd=top, capture_output=True)
    assert merge.returncode != 0 and "<<<<" in conflicted.read_text()


def test_snapshots_tell_created_from_changed_files(tmp_path):
    model, scene = tmp_path / "robot.xml", tmp_path / "scene.xml"
    model.write_text("a")
    before = snapshot([model, scene])
    scene.write_text("s")
    model.write_text("b")
    assert changes(before, snapshot([model, scene])) == ([str(scene)], [str(model)])
    model.write_text("b")  # rewritten with the same bytes: no change
    assert changes(snapshot([model, scene]), snapshot([model, scene])) == ([], [])


def test_git_status_names_untracked_and_ignored_files(tmp_path):
    _git("init", "-q", cwd=tmp_path)
    out = tmp_path / "mjcf"
    (out / "report").mkdir(parents=True)
    (out / "report" / ".gitignore").write_text("*\n")
    files = [out / "robot.xml", out / "scene.xml", out / "report" / "report.md"]
    for path in files:
        path.write_text("x")
    _git("add", "mjcf/scene.xml", cwd=tmp_path)
    untracked, ignored = git_status([str(p) for p in files])
    assert untracked == {str(out / "robot.xml")}
    assert ignored == {str(out / "report" / "report.md")}


def test_outside_a_work_tree_nothing_is_untracked(tmp_path):
    (tmp_path / "robot.xml").write_text("x")
    assert git_status([str(tmp_path / "robot.xml")]) == (set(), set())


def test_git_holds_committed_staged_and_conflicted_files_not_edits(tmp_path):
    """What a build may write over without losing anything: bytes HEAD has, and a file in a
    merge conflict (which a rebuild resolves); not an edit git lacks or holds only in its
    index (a commit hook would write over it), nor a file git does not track."""
    out = tmp_path / "mjcf"
    out.mkdir()
    names = ("committed.xml", "edited.xml", "staged.xml", "conflict.xml")
    _repo_with_a_conflict(tmp_path, [out / name for name in names], out / "conflict.xml")
    (out / "edited.xml").write_text("tuned by hand\n")
    (out / "staged.xml").write_text("tuned and staged\n")
    _git("add", "mjcf/staged.xml", cwd=tmp_path)
    (out / "untracked.xml").write_text("mine\n")
    names = ["committed.xml", "edited.xml", "staged.xml", "conflict.xml", "untracked.xml"]
    held = git_holds([str(out / name) for name in names])
    assert held == {str(out / name) for name in ("committed.xml", "conflict.xml")}
    assert git_holds([str(out / "conflict.xml"), str(tmp_path / "elsewhere.xml")]) == {
        str(out / "conflict.xml")
    }


def test_outside_a_work_tree_or_before_a_commit_git_holds_nothing(tmp_path):
    (tmp_path / "robot.xml").write_text("x")
    assert git_holds([str(tmp_path / "robot.xml")]) == set()
    _git("init", "-q", cwd=tmp_path)
    _git("add", "robot.xml", cwd=tmp_path)
    assert git_holds([str(tmp_path / "robot.xml")]) == set()


def test_git_holds_neither_hidden_changes_nor_conflicts_resolved_by_hand(tmp_path):
    """A file git is told not to look at (a local tweak kept out of commits) compared as
    unchanged, and a conflict resolved in an editor but not added counted as a conflict: the
    build wrote over both."""
    names = ("hidden.xml", "skipped.xml", "resolved.xml")
    _repo_with_a_conflict(tmp_path, [tmp_path / n for n in names], tmp_path / "resolved.xml")
    (tmp_path / "resolved.xml").write_text("merged by hand\n")
    _git("update-index", "--assume-unchanged", "hidden.xml", cwd=tmp_path)
    _git("update-index", "--skip-worktree", "skipped.xml", cwd=tmp_path)
    (tmp_path / "hidden.xml").write_text("local tweak\n")
    (tmp_path / "skipped.xml").write_text("local tweak\n")
    names = [str(tmp_path / name) for name in ("hidden.xml", "skipped.xml", "resolved.xml")]
    assert git_holds(names) == set()


def test_where_git_cannot_be_asked_it_says_so(tmp_path, monkeypatch):
    """No git on PATH in a git checkout: not "git has no commit of it", but why it cannot say."""
    from mjcfbuild.engine.published import GitUnavailable

    _git("init", "-q", cwd=tmp_path)
    (tmp_path / "robot.xml").write_text("x")
    monkeypatch.setenv("PATH", str(tmp_path / "nothing"))
    with pytest.raises(GitUnavailable, match="git is not installed"):
        git_holds([str(tmp_path / "robot.xml")])
