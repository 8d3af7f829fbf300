"""Where the package's LICENSE comes from, and the CHANGELOG's entries."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.check.results import CheckResults, Stand
from mjcfbuild.markup import markdown_text
from mjcfbuild.package.documents import Provenance, changelog, find_license, readme
from tests.page.hostile import CODE, PICTURE, PIPES, TAG, markup_outside_code


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


def test_names_in_the_readme_and_changelog_stay_text():
    info = Provenance(
        name=PIPES,
        source=f"urdf/{CODE}.urdf",
        manifest_text="name: robot\n# ``` a fence in a comment\n",
        revision="abc",
        remote=TAG,
        mjcfbuild_version="1.0",
        mujoco_version="3.3",
        license_from=PICTURE,
    )
    assembly = {
        "readiness": {"actuators": [{"type": TAG}], "home": [{"source": PICTURE}]},
        "repairs": [{"body": CODE, "problem": PIPES, "before": 1, "after": 2}],
        "warnings": [TAG],
    }
    text = readme(info, CheckResults(loads=True, failures=[PICTURE]), assembly)
    assert markup_outside_code(text) == []
    assert "name: robot\n# ``` a fence in a comment\n````" in text  # the block holds it whole
    assert text.startswith(f"# {markdown_text(PIPES)}\n")
    entry = changelog("", "abc", [markdown_text(f"joint {TAG}: range")])
    assert markup_outside_code(entry) == []


def test_the_readme_says_a_robot_stands_only_when_it_stood():
    """A robot that cannot stand without a controller passes its check; its README says why
    instead of claiming that it stands."""
    info = Provenance("r", "r.urdf", "name: r\n", "", "", "1.0", "3.3", "")
    stood = readme(info, CheckResults(loads=True, stand=Stand(seconds=5.0)), {})
    assert "- stands on the floor at home" in stood.splitlines()
    balancer = CheckResults(
        loads=True, stand=Stand(needs_controller="point feet"), needs_controller="point feet"
    )
    text = readme(info, balancer, {})
    assert "stands on the floor" not in text
    assert (
        "- the robot cannot stand without a controller (point feet): the stand test was not run"
        in text.splitlines()
    )
    fell = Stand(seconds=5.0, fell_without_controller="torque motors")
    motors = CheckResults(loads=True, stand=fell, needs_controller="torque motors")
    lines = readme(info, motors, {}).splitlines()
    assert "- the robot cannot stand without a controller (torque motors)" in lines


def test_a_folder_named_license_is_no_place_a_license_is_awaited(tmp_path):
    # The places looked at in vain are the stamp's absent files; a LICENSE folder there is
    # present to the stamp, which then sent every no-op to the full build (found in review).
    from mjcfbuild.package.documents import search_license

    (tmp_path / "pkg" / "urdf").mkdir(parents=True)
    (tmp_path / "pkg" / "package.xml").write_text("<package/>")
    (tmp_path / "pkg" / "LICENSE").mkdir()
    found, looked = search_license([tmp_path / "pkg" / "urdf"], None)
    assert found is None
    assert (tmp_path / "pkg" / "urdf" / "LICENSE").resolve() in looked
    assert (tmp_path / "pkg" / "LICENSE").resolve() not in looked
