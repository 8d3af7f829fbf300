"""Where the package's LICENSE comes from, and the CHANGELOG's entries."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.package.documents import changelog, find_license


def test_the_license_is_found_up_to_the_package_root_and_no_further(tmp_path: Path):
    package = tmp_path / "outer" / "robot_description"
    (package / "urdf").mkdir(parents=True)
    (tmp_path / "outer" / "LICENSE").write_text("outer")
    # outside a repo, a few folders up: the outer license is found...
    assert find_license([package / "urdf"], None) == tmp_path / "outer" / "LICENSE"
    # ...but not past the description package's own root
    (package / "package.xml").write_text("<package/>")
    assert find_license([package / "urdf"], None) is None
    (package / "COPYING").write_text("mine")
    assert find_license([package / "urdf"], None) == package / "COPYING"
    # in a repo, never above its top
    (package / "COPYING").unlink()
    (package / "package.xml").unlink()
    assert find_license([package / "urdf"], package) is None
    assert find_license([package / "urdf"], tmp_path) == tmp_path / "outer" / "LICENSE"


def test_changelog_entries_go_on_top_and_the_old_ones_stay():
    first = changelog("", "abc", ["packaged"])
    assert first == "# Changelog\n\n## abc\n\n- packaged\n"
    second = changelog(first + "\nhand-written note\n", "def", ["joint elbow: range"])
    assert second.startswith("# Changelog\n\n## def\n\n- joint elbow: range\n\n## abc\n")
    assert second.endswith("hand-written note\n")
