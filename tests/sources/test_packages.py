"""Finding ROS packages from the manifest and the ROS environment variables, without ROS."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.sources.packages import PackageResolver, find_enclosing_package
from tests.conftest import write


def package(folder, name):
    write(folder / "package.xml", f"<package><name>{name}</name></package>")
    return folder


def test_manifest_packages_come_first(tmp_path):
    explicit = package(tmp_path / "mine", "robot_description")
    other = package(tmp_path / "ws" / "robot_description", "robot_description")
    resolver = PackageResolver(
        {"robot_description": explicit}, {"ROS_PACKAGE_PATH": str(other.parent)}
    )
    assert resolver.find("robot_description") == explicit


def test_ros_package_path_is_crawled_by_package_xml_name(tmp_path):
    folder = package(tmp_path / "src" / "deep" / "folder_name", "real_name")
    resolver = PackageResolver({}, {"ROS_PACKAGE_PATH": str(tmp_path / "src")})
    assert resolver.find("real_name") == folder


def test_a_package_linked_into_a_workspace_is_found_and_a_link_loop_ends(tmp_path):
    """rospack follows linked folders (a package linked into src/ is a common layout); they
    were skipped ('unknown package')."""
    folder = package(tmp_path / "code" / "demo_description", "demo_description")
    source = tmp_path / "ws" / "src"
    source.mkdir(parents=True)
    (source / "demo_description").symlink_to(folder, target_is_directory=True)
    (source / "loop").symlink_to(source, target_is_directory=True)
    resolver = PackageResolver({}, {"ROS_PACKAGE_PATH": str(source)})
    assert resolver.find("demo_description") == source / "demo_description"


def test_ignore_markers_hide_packages(tmp_path):
    package(tmp_path / "src" / "hidden" / "pkg", "pkg")
    write(tmp_path / "src" / "hidden" / "COLCON_IGNORE", "")
    resolver = PackageResolver({}, {"ROS_PACKAGE_PATH": str(tmp_path / "src")})
    with pytest.raises(InputError):
        resolver.find("pkg")


def test_ament_prefix_path_uses_the_resource_index(tmp_path):
    prefix = tmp_path / "install"
    write(prefix / "share" / "ament_index" / "resource_index" / "packages" / "arm", "")
    (prefix / "share" / "arm").mkdir(parents=True)
    resolver = PackageResolver({}, {"AMENT_PREFIX_PATH": f"/nonexistent:{prefix}"})
    assert resolver.find("arm") == prefix / "share" / "arm"


def test_unknown_package_lists_known_ones_and_says_what_to_do(tmp_path):
    package(tmp_path / "src" / "a", "alpha")
    resolver = PackageResolver({"beta": tmp_path}, {"ROS_PACKAGE_PATH": str(tmp_path / "src")})
    with pytest.raises(InputError) as info:
        resolver.find("gamma")
    text = info.value.one_line()
    assert "unknown package 'gamma' (known packages: alpha, beta)" in text
    assert "under 'packages' in robot.yaml" in text


def test_manifest_package_that_is_not_a_folder(tmp_path):
    resolver = PackageResolver({"arm": tmp_path / "missing"}, {})
    with pytest.raises(InputError, match="not a folder"):
        resolver.find("arm")


def test_fingerprint_covers_map_and_environment(tmp_path):
    a = PackageResolver({"x": tmp_path}, {"ROS_PACKAGE_PATH": "/a"}).fingerprint()
    b = PackageResolver({"x": tmp_path}, {"ROS_PACKAGE_PATH": "/b"}).fingerprint()
    assert a != b


def test_enclosing_package(tmp_path):
    root = package(tmp_path / "arm_pkg", "arm_description")
    urdf = write(root / "urdf" / "arm.urdf", "<robot/>")
    assert find_enclosing_package(urdf) == ("arm_description", root)
    assert find_enclosing_package(write(tmp_path / "loose.urdf", "")) is None


def test_a_pattern_with_a_misspelt_word_gets_the_pattern_with_the_closest_word():
    from mjcfbuild.sources.packages import suggestion

    names = ["left_finger_joint", "right_finger_joint", "elbow"]
    assert suggestion(["*fingr*"], names) == "; did you mean '*finger*'?"
    assert suggestion(["elbw"], names) == "; did you mean 'elbow'?"
    assert suggestion(["*gripper*"], names) == ""


def test_a_name_no_package_can_have_is_said_to_be_one_not_to_be_added(tmp_path):
    """xacrodoc's mesh_with_spaces names package://pkg with spaces/...: the advice to add it
    under 'packages' led to robot.yaml's own refusal of the name."""
    with pytest.raises(InputError) as info:
        PackageResolver({}, {}).find("pkg with spaces")
    assert info.value.message.startswith("'pkg with spaces' is no ROS package name")
    assert "packages" not in (info.value.hint or "")


def test_init_and_convert_refuse_such_a_name_for_package(tmp_path):
    from tests.conftest import run_cli, two_link_urdf

    urdf = write(tmp_path / "robot.urdf", two_link_urdf())
    result = run_cli("init", "--package", f"pkg with spaces={tmp_path}", str(urdf), cwd=tmp_path)
    assert result.code == 2 and "'pkg with spaces' is no ROS package name" in result.stderr
    assert not (tmp_path / "robot.yaml").exists()


@pytest.mark.parametrize(
    ("name", "candidates", "offered"),
    [
        ("head", ["r_hand", "l_hand", "torso"], None),  # atlas_v3: three edits away
        ("j2", ["j1", "base"], "j1"),  # one edit, though difflib finds it too different
        ("elbw", ["elbow", "wrist"], "elbow"),
        ("shouldr_pan_jiont", ["shoulder_pan_joint", "elbow"], "shoulder_pan_joint"),
        ("zzzz_nothing", ["upper_arm"], None),
    ],
)
def test_a_suggestion_is_a_name_a_few_edits_away(name, candidates, offered):
    from mjcfbuild.sources.packages import did_you_mean

    assert did_you_mean(name, candidates) == (f"; did you mean '{offered}'?" if offered else "")


RENAMED = """<?xml version="1.0"?>
<package format="3">
  <!-- renamed from <name>old_parts</name> -->
  <description>parts: a <b><name>nested</name></b> name is not it</description>
  <name>my_parts</name><version>0.0.1</version></package>
"""


def test_the_name_is_the_package_elements_name_child_not_one_in_a_comment(tmp_path):
    """package.xml's <name> was found by a regex on the raw text: a commented-out earlier
    name was taken for it, and $(find my_parts) was refused, suggesting 'old_parts'."""
    folder = tmp_path / "src" / "parts_folder"
    write(folder / "package.xml", RENAMED)
    resolver = PackageResolver({}, {"ROS_PACKAGE_PATH": str(tmp_path / "src")})
    assert resolver.find("my_parts") == folder
    with pytest.raises(InputError, match=r"known packages: my_parts\)"):
        resolver.find("old_parts")
    urdf = write(folder / "urdf" / "part.urdf", "<robot/>")
    assert find_enclosing_package(urdf) == ("my_parts", folder)


def test_init_finds_a_renamed_package_by_its_name(tmp_path):
    from mjcfbuild.sources.infer import find_package_xml

    folder = tmp_path / "ws" / "parts_folder"
    write(folder / "package.xml", RENAMED)
    source = write(tmp_path / "ws" / "robot" / "robot.urdf.xacro", "<robot/>")
    assert find_package_xml("my_parts", source) == [folder]
    assert find_package_xml("old_parts", source) == []


@pytest.mark.parametrize(
    "text",
    ["<package><name>", "<robot><name>arm</name></robot>", "<package><version/></package>"],
    ids=["not-xml", "not-a-package", "no-name"],
)
def test_a_package_xml_without_a_readable_name_falls_back_to_its_folder(tmp_path, text):
    folder = tmp_path / "src" / "arm"
    write(folder / "package.xml", text)
    resolver = PackageResolver({}, {"ROS_PACKAGE_PATH": str(tmp_path / "src")})
    assert resolver.find("arm") == folder


def test_a_typo_is_a_few_edits_and_at_most_half_the_name():
    from mjcfbuild.sources.packages import within_edits

    assert within_edits("prat", {"part"}, 2)  # a transposition
    assert within_edits("use_gazeb", {"use_gazebo"}, 2)
    assert not within_edits("use_gazebo_gui", {"use_gazebo"}, 2)  # four edits
    # Every short name is an edit or two from every other: no typo of any of them.
    assert not within_edits("x", {"y"}, 2) and not within_edits("ab", {"cd"}, 2)
    assert not within_edits("part", {"part"}, 2)  # itself is no typo
