"""What a build publishes, whether it changed, and what git does not track yet (real git)."""

from __future__ import annotations

import subprocess

from mjcfbuild.engine.published import changes, git_status, snapshot


def _git(*args: str, cwd) -> None:
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True)


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
