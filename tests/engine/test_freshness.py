"""``check --up-to-date`` and ``check`` judge a folder by the graph ``build`` plans."""

from __future__ import annotations

import shutil

from tests.conftest import run_cli, simple_manifest, two_link_urdf, write


def test_a_package_built_with_the_check_is_up_to_date_until_an_input_changes(tmp_path):
    # The package's README and picture read the check's results: the status graph of check
    # --up-to-date plans them as the build did, instead of a package without the check.
    write(tmp_path / "robot.urdf", two_link_urdf())
    simple_manifest(tmp_path, extra="output:\n  folder: mjcf\n  package: true\n")
    assert run_cli("build", "-j", "1", cwd=tmp_path).code == 0
    fresh = run_cli("check", "--up-to-date", cwd=tmp_path)
    assert fresh.code == 0, fresh.stderr
    checked = run_cli("check", cwd=tmp_path)
    assert checked.code == 0 and "out of date" not in checked.stdout + checked.stderr
    # A fresh clone (no build database) is judged by a rebuild, which checks where the
    # package reads the check: the same bytes, the CHANGELOG's history left out.
    clone = tmp_path / "clone"
    shutil.copytree(tmp_path, clone, ignore=shutil.ignore_patterns(".mjcfbuild"))
    changelog = clone / "mjcf" / "package" / "CHANGELOG.md"
    changelog.write_text(changelog.read_text() + "\nan earlier entry\n")
    cloned = run_cli("check", "--up-to-date", cwd=clone)
    assert cloned.code == 0, cloned.stderr
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(urdf.read_text().replace('<mass value="1"/>', '<mass value="1.5"/>', 1))
    stale = run_cli("check", "--up-to-date", cwd=tmp_path)
    assert stale.code == 6 and "expand robot.urdf" in stale.stderr
    assert run_cli("build", "-j", "1", "--no-check", cwd=tmp_path).code == 0
    # A package written without the check is not the one `mjcfbuild build` writes.
    unchecked = run_cli("check", "--up-to-date", cwd=tmp_path)
    assert unchecked.code == 6 and "package package/" in unchecked.stderr
