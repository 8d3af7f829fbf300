"""What ``mjcfbuild watch`` watches: a real build's stamp, or the files around the manifest."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import mjcfbuild
from mjcfbuild.cli import run
from mjcfbuild.engine.watched import MUJOCO_LOG, Watched, around, from_stamp, without_stamp
from tests.conftest import ROOT


def files(paths: list[str]) -> list[str]:
    """The files of what is watched (a folder's path ends with os.sep)."""
    return [path for path in paths if not path.endswith(os.sep)]


def folders(paths: list[str]) -> list[str]:
    """The folders of what is watched, by the names of their files."""
    return [path for path in paths if path.endswith(os.sep)]


def test_after_a_build_it_watches_what_the_stamp_lists_as_recorded(arm):
    assert run(["build", str(arm / "robot.yaml"), "-q", "--no-check"]) == 0
    watched = from_stamp(arm / "robot.yaml", run_check=False)
    assert watched is not None and watched.changed() == []
    names = set(watched.records)
    xacro, model = str(arm / "urdf" / "arm.urdf.xacro"), str(arm / "mjcf" / "example_arm.xml")
    assert {xacro, str(arm / "meshes" / "forearm.obj"), model} <= names
    assert model in watched.written and xacro not in watched.written
    package = Path(mjcfbuild.__file__).parent
    assert str(package / "cli" / "watch.py") in watched.code  # its own code ends the watch
    assert xacro not in watched.code

    for path in (arm / "meshes").iterdir():
        os.utime(path)  # touched: changed, but not edited
    mesh = arm / "meshes" / "forearm.obj"
    mesh.write_text(mesh.read_text().replace(" 0.240000", " 0.250000"))
    changed = watched.changed()
    assert str(mesh) in changed and len(changed) == len(list((arm / "meshes").iterdir()))
    assert watched.edited(changed) == [str(mesh)]
    assert from_stamp(arm / "no-such.yaml", run_check=False) is None


def test_without_a_stamp_it_watches_the_folder_but_not_what_builds_write(tmp_path):
    robot = tmp_path / "robot"
    for name in (
        "robot.yaml",
        "urdf/robot.urdf",
        "meshes/a.stl",
        ".git/HEAD",  # version control
        "mjcf/robot.xml",  # an output folder: it holds a build's state folder
        "mjcf/.mjcfbuild/plan.json",
        MUJOCO_LOG,
        "exported/robot.urdf",  # written by the last good build
    ):
        (robot / name).parent.mkdir(parents=True, exist_ok=True)
        (robot / name).write_text(name)
    elsewhere = tmp_path / "shared" / "common.xacro"  # read by the last good build
    elsewhere.parent.mkdir()
    elsewhere.write_text("")
    last_good = Watched.take([str(elsewhere), str(robot / "exported/robot.urdf")])
    last_good.written = frozenset({str(robot / "exported/robot.urdf")})
    kept = (robot / "robot.yaml", robot / "urdf/robot.urdf", robot / "meshes/a.stl", elsewhere)
    assert files(around(robot / "robot.yaml", last_good)) == sorted(str(path) for path in kept)
    # and the folders walked, by their files' names, but those builds write into
    assert folders(around(robot / "robot.yaml", last_good)) == [
        f"{robot / name}{os.sep}" for name in ("", "meshes", "urdf")
    ]


def test_without_a_stamp_what_builds_wrote_into_the_manifests_own_folder_is_not_watched(arm):
    """output.folder '.': the outputs lie beside the inputs. A build that fails after writing
    them (a failed check) must not count as an edit that starts the next build: what builds
    recorded writing there is left out, the rest is watched."""
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("folder: mjcf", "folder: ."))
    assert run(["build", str(manifest), "-q", "--no-check"]) == 0
    watched = around(manifest, None)
    assert str(arm / "example_arm.xml") not in watched
    assert str(arm / "scene.xml") not in watched
    assert not any(path.startswith(str(arm / "assets")) for path in watched)
    assert {str(manifest), str(arm / "urdf" / "arm.urdf.xacro")} <= set(watched)
    assert str(arm / "meshes" / "forearm.obj") in watched
    # A record that cannot be read leaves out nothing but the state folder.
    (arm / ".mjcfbuild" / "written.json").write_text("[")
    assert str(arm / "example_arm.xml") in around(manifest, None)


def test_without_a_stamp_the_file_its_own_output_goes_to_is_not_watched(tmp_path):
    """``mjcfbuild watch > watch.txt`` in the robot's folder: each line it printed changed a
    watched file, and after a failed build it built again and again without end."""
    robot = tmp_path / "robot"
    robot.mkdir()
    (robot / "robot.yaml").write_text("name: [\n")
    script = (
        "import sys; from pathlib import Path; from mjcfbuild.engine.watched import around; "
        "print('printed', flush=True); "
        "sys.stderr.write(repr([p for p in around(Path(sys.argv[1]), None) if p[-1] != '/']))"
    )
    with open(robot / "watch.txt", "w") as output:
        done = subprocess.run(
            [sys.executable, "-c", script, str(robot / "robot.yaml")],
            stdout=output,
            stderr=subprocess.PIPE,
            text=True,
            env={**os.environ, "PYTHONPATH": str(ROOT)},
            check=True,
        )
    assert (robot / "watch.txt").read_text() == "printed\n"
    assert done.stderr == repr([str(robot / "robot.yaml")])


def test_without_a_stamp_it_watches_the_source_and_package_folders_it_names(tmp_path):
    """A fix in a package beside the manifest's folder is seen too, even when the manifest is
    what failed validation (it is read as plain YAML); one that is not YAML names none."""
    robot, arm = tmp_path / "robot", tmp_path / "arm"
    (arm / "urdf").mkdir(parents=True)
    (arm / "urdf" / "arm.urdf.xacro").write_text("<robot/>")
    (arm / "meshes" / "mjcf" / ".mjcfbuild").mkdir(parents=True)  # an output folder there
    (arm / "meshes" / "mjcf" / "model.xml").write_text("")
    robot.mkdir()
    manifest = robot / "robot.yaml"
    manifest.write_text(
        "name: arm\nsource: {xacro: ../arm/urdf/arm.urdf.xacro}\n"
        "packages: {arm_description: ../arm, gone: ../nowhere}\noptions: {no_such_option: 1}\n"
    )
    watched = files(around(manifest, None))
    assert watched == [str(arm / "urdf" / "arm.urdf.xacro"), str(manifest)]
    manifest.write_text(manifest.read_text() + "scene: [\n")  # not YAML any more
    assert files(around(manifest, None)) == [str(manifest)]


def test_without_a_stamp_a_file_is_compared_with_what_it_was_when_the_build_began(tmp_path):
    """A fix saved while a failing build still ran is seen afterwards."""
    manifest = tmp_path / "robot.yaml"
    manifest.write_text("name: a\n")
    before = Watched.take(around(manifest, None))
    manifest.write_text("name: robot\n")  # during the build
    (tmp_path / "new.urdf").write_text("<robot/>")  # made during the build: the build may
    watched = without_stamp(manifest, None, before)  # have looked for it, so it counts too
    assert watched.changed() == [f"{tmp_path}{os.sep}", str(manifest)]
    assert watched.edited(watched.changed()) == [str(tmp_path / "new.urdf"), str(manifest)]


def test_after_a_build_stopped_at_an_edited_output_settling_it_is_seen(arm):
    """A build that stops at a model edited by hand (exit 7) is settled by moving the model
    away: the watch saw only the inputs after a failed build, and waited on."""
    manifest = arm / "robot.yaml"
    assert run(["build", str(manifest), "-q", "--no-check"]) == 0
    last_good = from_stamp(manifest, run_check=False)
    model = arm / "mjcf" / "example_arm.xml"
    model.write_text(model.read_text() + "<!-- tuned -->\n")
    before = Watched.take(around(manifest, last_good))
    assert run(["build", str(manifest), "-q", "--no-check"]) == 7
    watched = without_stamp(manifest, last_good, before)
    assert watched.changed() == []  # what the failed build wrote starts nothing
    model.rename(arm / "tuned.xml")
    assert str(model) in watched.changed()


def test_after_a_build_a_file_that_comes_to_match_a_pattern_it_searched_is_a_change(tmp_path):
    # The SRDF the build looks for beside a floating robot's description: watch waited on.
    from tests.conftest import file_clock_past_changes, two_link_urdf, write

    write(tmp_path / "robot.urdf", two_link_urdf())
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource:\n  urdf: robot.urdf\noptions:\n  free_joint: true\n",
    )
    file_clock_past_changes(tmp_path)  # else the build leaves no stamp to watch by
    assert run(["build", str(tmp_path / "robot.yaml"), "-q", "--no-check"]) == 0
    watched = from_stamp(tmp_path / "robot.yaml", run_check=False)
    assert watched is not None and watched.changed() == []
    srdf = write(tmp_path / "config" / "two_link.srdf", "<robot name='two_link'/>\n")
    changed = watched.changed()
    assert str(tmp_path / "config") + os.sep in changed
    assert str(srdf) in watched.edited(changed)


def test_after_a_build_a_file_added_where_a_pattern_s_folder_part_matched_is_a_change(tmp_path):
    # A sibling MoveIt package's config/ (the pattern */..._moveit_config/config/*.srdf): the
    # folder above it lists no change when a file comes in it.
    from tests.conftest import file_clock_past_changes, two_link_urdf, write

    write(tmp_path / "top" / "desc" / "urdf" / "robot.urdf", two_link_urdf())
    (tmp_path / "top" / "r_moveit_config" / "config").mkdir(parents=True)
    manifest = tmp_path / "top" / "desc" / "urdf" / "robot.yaml"
    write(manifest, "name: r\nsource:\n  urdf: robot.urdf\noptions:\n  free_joint: true\n")
    file_clock_past_changes(tmp_path)  # else the build leaves no stamp to watch by
    assert run(["build", str(manifest), "-q", "--no-check"]) == 0
    watched = from_stamp(manifest, run_check=False)
    assert watched is not None and watched.changed() == []
    srdf = write(tmp_path / "top" / "r_moveit_config" / "config" / "r.srdf", "<robot name='r'/>\n")
    assert str(srdf) in watched.edited(watched.changed())
