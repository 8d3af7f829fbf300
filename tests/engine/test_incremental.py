"""The acceptance of incremental builds: exactly the tasks whose inputs changed run."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import mujoco
import numpy as np
import pytest
import trimesh

import mjcfbuild
from mjcfbuild import filesig
from mjcfbuild.errors import BuildFailed
from tests.conftest import (
    file_clock_past,
    file_clock_past_changes,
    run_cli,
    two_link_urdf,
    write,
)

ALL_ARM_TASKS = {
    "expand",
    "plan",
    "mesh:base",
    "mesh:finger",
    "mesh:forearm",
    "mesh:upper_arm",
    "selfcollision",
    "assemble",
    "scene",
}


def build(folder, jobs=2):
    # The check and previews are left out here; test_check_follows_the_model covers them.
    return mjcfbuild.build(folder / "robot.yaml", jobs=jobs, check=False)


@pytest.fixture
def built_arm(arm):
    result = build(arm)
    assert set(result.ran) == ALL_ARM_TASKS
    return arm


def test_cold_build_loads_and_simulates(built_arm):
    model = mujoco.MjModel.from_xml_path(str(built_arm / "mjcf" / "scene.xml"))
    data = mujoco.MjData(model)
    for _ in range(2000):
        mujoco.mj_step(model, data)
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))


def test_second_build_runs_nothing_and_says_so(built_arm):
    result = build(built_arm)
    assert result.ran == []
    assert "0 run, 9 up to date" in result.summary()


def test_touching_every_input_runs_nothing(built_arm):
    later = time.time() + 100
    for path in built_arm.rglob("*"):
        if path.is_file() and "mjcf" not in path.parts:
            os.utime(path, (later, later))
    assert build(built_arm).ran == []


def test_editing_one_mesh_reruns_that_mesh_and_the_assembly(built_arm):
    mesh = built_arm / "meshes" / "finger.stl"
    data = bytearray(mesh.read_bytes())
    data[84 + 12] ^= 0x01  # nudge one vertex of the first triangle
    mesh.write_bytes(bytes(data))
    # The finger collides with authored primitives: the collision matrix stays up to date.
    assert sorted(build(built_arm).ran) == ["assemble", "mesh:finger"]


def test_a_same_size_edit_with_its_mtime_restored_reruns_what_it_feeds(arm, monkeypatch):
    """The engine's hash cache trusts a file only when size, mtime, ctime, inode and device
    all agree: an edit that kept the size and had its time restored is still an edit."""
    monkeypatch.setattr(filesig, "RACY_NS", 0)  # remember every hash: only ctime can tell
    hour_ago = time.time() - 3600
    for path in arm.rglob("*"):
        if path.is_file():
            os.utime(path, (hour_ago, hour_ago))
    assert set(build(arm).ran) == ALL_ARM_TASKS
    finger = arm / "urdf" / "finger.xacro"
    before = os.stat(finger)
    file_clock_past(arm, before.st_ctime_ns)
    finger.write_text(finger.read_text().replace('<mass value="0.02"/>', '<mass value="0.03"/>'))
    os.utime(finger, ns=(before.st_atime_ns, before.st_mtime_ns))
    assert (os.stat(finger).st_size, os.stat(finger).st_ino) == (before.st_size, before.st_ino)
    assert sorted(build(arm).ran) == ["assemble", "expand", "plan"]
    assert 'mass="0.03"' in (arm / "mjcf" / "example_arm.xml").read_text()


def test_editing_an_included_xacro_reruns_expansion_and_what_depends_on_it(built_arm):
    finger = built_arm / "urdf" / "finger.xacro"
    finger.write_text(finger.read_text().replace('<mass value="0.02"/>', '<mass value="0.03"/>'))
    # A mass does not decide contacts: the collision matrix stays up to date.
    assert sorted(build(built_arm).ran) == ["assemble", "expand", "plan"]


def test_a_change_that_does_not_change_the_urdf_stops_after_expansion(built_arm):
    finger = built_arm / "urdf" / "finger.xacro"
    finger.write_text(finger.read_text() + "\n<!-- a comment outside the robot -->\n")
    assert build(built_arm).ran == ["expand"]


def test_editing_yaml_loaded_by_xacro_reruns_expansion(built_arm):
    limits = built_arm / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    assert sorted(build(built_arm).ran) == ["assemble", "expand", "plan", "selfcollision"]


def test_changing_a_xacro_arg_reruns_expansion(built_arm):
    manifest = built_arm / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("with_camera: true", "with_camera: false"))
    assert sorted(build(built_arm).ran) == ["assemble", "expand", "plan", "selfcollision"]


def test_changing_an_option_reruns_only_the_assembly(built_arm):
    manifest = built_arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "options:\n  fuse_static: false\n")
    assert sorted(build(built_arm).ran) == ["assemble", "selfcollision"]


def test_deleted_outputs_are_rebuilt_and_edited_ones_kept(built_arm):
    robot = built_arm / "mjcf" / "example_arm.xml"
    original = robot.read_bytes()
    (built_arm / "mjcf" / "assets" / "finger.obj").unlink()
    assert build(built_arm).ran == ["assemble"]
    assert (built_arm / "mjcf" / "assets" / "finger.obj").exists()
    robot.unlink()
    assert build(built_arm).ran == ["assemble"]
    assert robot.read_bytes() == original
    tuned = original.replace(b'mass="2"', b'mass="3"')
    robot.write_bytes(tuned)
    with pytest.raises(BuildFailed, match="was edited since a build wrote it"):
        build(built_arm)
    assert robot.read_bytes() == tuned
    # A mesh changed too: the assembly stops before any asset changes, so the tuned model
    # is not left pointing at new geometry.
    assets = {p.name: p.read_bytes() for p in (built_arm / "mjcf" / "assets").iterdir()}
    forearm = built_arm / "meshes" / "forearm.obj"
    forearm.write_text(forearm.read_text().replace("0.240000", "0.270000"))
    with pytest.raises(BuildFailed, match="was edited since a build wrote it"):
        build(built_arm)
    assert {p.name: p.read_bytes() for p in (built_arm / "mjcf" / "assets").iterdir()} == assets


def test_removed_mesh_disappears_from_assets(built_arm):
    xacro = built_arm / "urdf" / "arm.urdf.xacro"
    text = xacro.read_text().replace(
        '<geometry><mesh filename="package://arm_description/meshes/base.stl"/></geometry>',
        '<geometry><cylinder radius="0.08" length="0.1"/></geometry>',
    )
    xacro.write_text(text)
    build(built_arm)
    assert not (built_arm / "mjcf" / "assets" / "base.obj").exists()
    assert not (built_arm / "mjcf" / ".mjcfbuild" / "products" / "base").exists()


def test_an_asset_the_user_edited_is_kept_when_the_model_stops_using_it(built_arm):
    """Unused assets go, but not one edited since the build wrote it: no build could write
    the user's bytes back."""
    edited = built_arm / "mjcf" / "assets" / "base.obj"
    edited.write_text(edited.read_text() + "# my edit\n")
    xacro = built_arm / "urdf" / "arm.urdf.xacro"
    xacro.write_text(
        xacro.read_text().replace(
            '<geometry><mesh filename="package://arm_description/meshes/base.stl"/></geometry>',
            '<geometry><cylinder radius="0.08" length="0.1"/></geometry>',
        )
    )
    result = build(built_arm)
    assert edited.read_text().endswith("# my edit\n")
    assert any(
        warning.startswith("assets/base.obj: edited since mjcfbuild wrote it, and the model no ")
        for warning in result.warnings
    ), result.warnings


def test_environment_variables_read_by_xacro_are_dependencies(tmp_path, monkeypatch):
    write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<link name="$(optenv LINK_NAME base)"/></robot>',
    )
    write(tmp_path / "robot.yaml", "name: r\nsource:\n  xacro: r.xacro\n")
    monkeypatch.delenv("LINK_NAME", raising=False)
    build(tmp_path)
    assert build(tmp_path).ran == []
    monkeypatch.setenv("LINK_NAME", "torso")
    assert "expand" in build(tmp_path).ran
    assert 'name="torso"' in (tmp_path / "mjcf" / "r.xml").read_text()


def test_a_file_added_to_a_xacro_include_pattern_is_built_in(tmp_path):
    """xacro:include of parts/*.xacro: a part added or removed later left the old model,
    and the no-op said it was current."""
    part = (
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="{0}">'
        '<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" '
        'izz="0.01"/></inertial></link><joint name="{0}_joint" type="fixed">'
        '<parent link="base"/><child link="{0}"/></joint></robot>'
    )
    write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base">'
        '<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" '
        'izz="0.01"/></inertial></link><xacro:include filename="parts/*.xacro"/></robot>',
    )
    write(tmp_path / "parts" / "a.xacro", part.format("a"))
    write(tmp_path / "robot.yaml", "name: r\nsource:\n  xacro: r.xacro\n")
    assert run_cli("build", "--no-check", "-q", cwd=tmp_path).code == 0
    write(tmp_path / "parts" / "b.xacro", part.format("b"))
    stale = run_cli("check", "--up-to-date", cwd=tmp_path)
    assert stale.code == 6 and "parts/*.xacro changed" in stale.stdout + stale.stderr
    assert run_cli("build", "--no-check", "-q", cwd=tmp_path).code == 0
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "r.xml"))
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "b") >= 0  # the new part's link
    (tmp_path / "parts" / "b.xacro").unlink()
    assert "expand" in build(tmp_path).ran


def test_a_failed_build_leaves_no_output_that_looks_current(built_arm):
    robot = built_arm / "mjcf" / "example_arm.xml"
    before = robot.read_bytes()
    finger = built_arm / "meshes" / "finger.stl"
    good = finger.read_bytes()
    finger.write_bytes(b"not a mesh at all")
    with pytest.raises(BuildFailed) as info:
        build(built_arm)
    assert "finger.stl" in info.value.one_line()
    assert robot.read_bytes() == before  # the old model stays, not a half-written one
    finger.write_bytes(good)
    result = build(built_arm)
    assert "mesh:finger" in result.ran and robot.read_bytes() == before


def test_check_follows_the_model(arm):
    ran = mjcfbuild.build(arm / "robot.yaml", jobs=2).ran
    assert {"check", "previews"} <= set(ran)
    assert mjcfbuild.build(arm / "robot.yaml", jobs=2).ran == []
    mesh = arm / "meshes" / "finger.stl"
    data = bytearray(mesh.read_bytes())
    data[84 + 12] ^= 0x01
    mesh.write_bytes(bytes(data))
    assert sorted(mjcfbuild.build(arm / "robot.yaml", jobs=2).ran) == [
        "assemble",
        "check",
        "mesh:finger",
        "previews",
        "tuning",
    ]


def test_a_mesh_deleted_after_a_build_gives_the_clean_build_message(arm):
    from mjcfbuild.errors import EXIT_INPUT

    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    (arm / "meshes" / "base.stl").unlink()
    after_build = run_cli("build", "-q", "--no-check", cwd=arm)
    assert run_cli("clean", cwd=arm).code == 0
    after_clean = run_cli("build", "-q", "--no-check", cwd=arm)
    assert after_clean.code == EXIT_INPUT
    error = [line for line in after_clean.stderr.splitlines() if "error" in line]
    assert error and "base.stl" in error[0] and "source.urdf:20" in error[0], after_clean.stderr
    assert after_build.code == EXIT_INPUT, after_build.stderr
    assert [line for line in after_build.stderr.splitlines() if "error" in line] == error


def test_a_xacro_argument_that_swaps_an_include_runs_expansion_once(built_arm):
    """The expansion reads another file: counted and printed once (it ran twice, 6 lines for
    5 counted, when the file it no longer read stayed among its dependencies)."""
    xacro = built_arm / "urdf" / "arm.urdf.xacro"
    write(built_arm / "urdf" / "finger2.xacro", (built_arm / "urdf" / "finger.xacro").read_text())
    xacro.write_text(
        xacro.read_text()
        .replace("/urdf/finger.xacro", "/urdf/$(arg finger).xacro")
        .replace("<xacro:include", '<xacro:arg name="finger" default="finger"/><xacro:include', 1)
    )
    assert run_cli("build", "-q", "--no-check", cwd=built_arm).code == 0
    manifest = built_arm / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("  args:\n", "  args:\n    finger: finger2\n"))
    result = run_cli("build", "--no-check", "-j", "1", cwd=built_arm)
    assert result.code == 0, result.stderr
    lines = [line for line in result.stdout.splitlines() if line.startswith("[")]
    assert sum("expand" in line for line in lines) == 1, result.stdout
    assert f"{len(lines)} run," in result.stdout, result.stdout


SRDF_PAIRS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="pairs">
    <group name="arm"><joint name="hinge"/></group>{state}
    <disable_collisions link1="base" link2="arm" reason="Never"/>
  </xacro:macro>
</robot>
"""
HOME = '<group_state name="home" group="arm"><joint name="hinge" value="0.5"/></group_state>'


def test_the_files_an_srdf_xacro_includes_are_its_inputs(tmp_path):
    # The srdf task keeps what its xacro included in a depfile, as expand does: declared on
    # the next plan, and in the no-op stamp, so an edit of one is never "up to date".
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "pkg" / "pairs.xacro", SRDF_PAIRS.format(state=""))
    write(
        tmp_path / "pkg" / "robot.srdf.xacro",
        '<?xml version="1.0"?>\n<robot name="two_link" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="pairs.xacro"/>\n  <xacro:pairs/>\n</robot>\n',
    )
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource:\n  urdf: robot.urdf\nself_collision: {srdf: pkg/robot.srdf.xacro}\n",
    )
    assert run_cli("build", "--no-check", "-j", "1", cwd=tmp_path).code == 0
    write(tmp_path / "pkg" / "pairs.xacro", SRDF_PAIRS.format(state=HOME))
    edited = run_cli("build", "--no-check", "-j", "1", cwd=tmp_path)
    assert edited.code == 0 and "srdf pkg/robot.srdf.xacro" in edited.stdout + edited.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "r.xml"))
    assert model.key_qpos[0][0] == pytest.approx(0.5)
    again = run_cli("build", "--no-check", "-j", "1", cwd=tmp_path)
    assert again.code == 0 and " 0 run, " in again.stdout + again.stderr
    full = run_cli(
        "build", "--no-check", "-j", "1", cwd=tmp_path, env={"MJCFBUILD_FULL_BUILD": "1"}
    )
    assert full.code == 0 and " 0 run, " in full.stdout + full.stderr  # doit's own test agrees
    current = run_cli("check", "--up-to-date", cwd=tmp_path)
    assert current.code == 0, current.stderr


def test_a_depfile_of_a_task_no_longer_planned_is_not_an_input(tmp_path):
    # robot.yaml stops naming the SRDF: its task's depfile stays in the state folder, but the
    # files it lists are no longer inputs, so removing them leaves the folder up to date (the
    # stamp read every *.deps.json and sent each later no-op to the full build).
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "pkg" / "pairs.xacro", SRDF_PAIRS.format(state=""))
    write(
        tmp_path / "pkg" / "robot.srdf.xacro",
        '<?xml version="1.0"?>\n<robot name="two_link" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="pairs.xacro"/>\n  <xacro:pairs/>\n</robot>\n',
    )
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource:\n  urdf: robot.urdf\nself_collision: {srdf: pkg/robot.srdf.xacro}\n",
    )
    assert run_cli("build", "--no-check", "-j", "1", cwd=tmp_path).code == 0
    write(tmp_path / "robot.yaml", "name: r\nsource:\n  urdf: robot.urdf\n")
    file_clock_past_changes(tmp_path)  # else the build leaves no stamp
    assert run_cli("build", "--no-check", "-j", "1", cwd=tmp_path).code == 0
    shutil.rmtree(tmp_path / "pkg")
    probe = (
        "from mjcfbuild.engine.stamp import nothing_to_do; "
        "print(nothing_to_do('robot.yaml', run_check=False) is not None)"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe], cwd=tmp_path, capture_output=True, text=True, check=True
    )
    assert done.stdout.strip() == "True"
    full = run_cli(
        "build", "--no-check", "-j", "1", cwd=tmp_path, env={"MJCFBUILD_FULL_BUILD": "1"}
    )
    assert full.code == 0 and " 0 run, " in full.stdout + full.stderr


STANDING_SRDF = (
    '<?xml version="1.0"?>\n<robot name="two_link"><group name="all"><joint name="hinge"/>'
    '</group><group_state name="standing" group="all"><joint name="hinge" value="0.5"/>'
    "</group_state></robot>\n"
)


def test_an_srdf_added_beside_a_floating_robot_s_description_is_an_edit(tmp_path):
    # The build looks for an SRDF beside a floating robot's description for its standing
    # pose; one added after a build was seen by the full graph but not by the no-op stamp
    # (found on g1: 'built g1.xml: 0 run' and the old keyframe).
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource:\n  urdf: robot.urdf\noptions:\n  free_joint: true\n",
    )
    file_clock_past_changes(tmp_path)  # else the build leaves no stamp
    assert run_cli("build", "--no-check", "-j", "1", cwd=tmp_path).code == 0
    write(tmp_path / "config" / "two_link.srdf", STANDING_SRDF)
    again = run_cli("build", "--no-check", "-j", "1", cwd=tmp_path)
    assert again.code == 0 and " 0 run, " not in again.stdout + again.stderr, again.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "r.xml"))
    assert model.key_qpos[0][7] == pytest.approx(0.5)


@pytest.mark.parametrize("variable", ["ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH"])
def test_a_package_that_comes_to_shadow_the_one_read_is_an_edit(tmp_path, variable):
    # A package built into an overlay already on the path (or copied into an earlier folder)
    # shadows the one the build read, though the variable's value stays: the fast path, the
    # full graph and check --up-to-date all called the old model current.
    def package(root: Path, size: str) -> None:
        folder = root / "share" / "arm_pkg" if variable == "AMENT_PREFIX_PATH" else root / "arm_pkg"
        write(folder / "package.xml", "<package><name>arm_pkg</name></package>\n")
        cube = trimesh.creation.box(extents=[2 * float(size)] * 3)
        write(folder / "meshes" / "box.obj", cube.export(file_type="obj"))

    package(tmp_path / "under", "0.1")
    urdf = two_link_urdf().replace(
        '<box size="0.2 0.2 0.1"/>', '<mesh filename="package://arm_pkg/meshes/box.obj"/>'
    )
    write(tmp_path / "robot" / "robot.urdf", urdf)
    write(tmp_path / "robot" / "robot.yaml", "name: r\nsource:\n  urdf: robot.urdf\n")
    paths = os.pathsep.join(str(tmp_path / name) for name in ("over", "under"))
    (tmp_path / "over").mkdir()
    env = {variable: paths}
    file_clock_past_changes(tmp_path)  # else the build leaves no stamp
    assert run_cli("build", "-j", "1", cwd=tmp_path / "robot", env=env).code == 0
    current = run_cli("check", "--up-to-date", cwd=tmp_path / "robot", env=env)
    assert current.code == 0, current.stdout + current.stderr
    package(tmp_path / "over", "0.3")
    stale = run_cli("check", "--up-to-date", cwd=tmp_path / "robot", env=env)
    assert stale.code != 0, stale.stdout + stale.stderr
    again = run_cli("build", "-j", "1", cwd=tmp_path / "robot", env=env)
    assert again.code == 0 and " 0 run, " not in again.stdout + again.stderr, again.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "robot" / "mjcf" / "r.xml"))
    assert model.mesh_vert[:, 0].max() == pytest.approx(0.3, abs=1e-6)
