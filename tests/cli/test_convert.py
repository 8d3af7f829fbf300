"""``mjcfbuild convert``: the reference converter's flags, run through the same build graph."""

from __future__ import annotations

import mujoco

from mjcfbuild.errors import EXIT_OK, EXIT_USAGE
from tests.conftest import two_link_urdf, write


def test_convert_urdf_into_output_folder_and_again_incrementally(cli, tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    result = cli("convert", "-u", "robot.urdf", "-o", "out", "-s", "-c", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert (tmp_path / "out" / "mujoco_description_formatted.xml").exists()
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "scene.xml"))
    assert model.njnt == 1
    again = cli("convert", "-u", "robot.urdf", "-o", "out", "-s", cwd=tmp_path)
    assert "0 run," in again.stdout


def test_the_summary_names_a_check_command_that_works_without_a_manifest(cli, tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    result = cli("convert", "-u", "robot.urdf", "-o", "out", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    command = "mjcfbuild check --urdf robot.urdf --mjcf out/mujoco_description_formatted.xml"
    assert f"(each check: `{command}`)" in result.stdout
    again = cli("convert", "-u", "robot.urdf", "-o", "out", cwd=tmp_path)  # the no-op's too
    assert f"(each check: `{command}`)" in again.stdout
    checked = cli(*command.split()[1:], cwd=tmp_path)
    assert checked.code == EXIT_OK and "mjcfbuild: check passed" in checked.stdout


def test_convert_robot_description_string(cli, tmp_path):
    result = cli("convert", "-r", two_link_urdf(), "-o", "out", "-f", "--no-fuse", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "scene.xml"))
    assert model.nq == 8  # free joint + hinge


def test_ros_args_a_launch_file_appends_are_dropped_as_the_reference_drops_them(cli, tmp_path):
    """A ROS 2 launch file runs the converter as a node: `--ros-args -r __node:=x --` was
    refused as an unknown option."""
    write(tmp_path / "robot.urdf", two_link_urdf())
    args = ["--ros-args", "-r", "__node:=converter", "-p", "use_sim_time:=true"]
    result = cli("convert", "-u", "robot.urdf", *args, "--", "-o", "out", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert (tmp_path / "out" / "scene.xml").exists()
    at_the_end = cli("convert", "-u", "robot.urdf", "-o", "out", *args, cwd=tmp_path)
    assert at_the_end.code == EXIT_OK, at_the_end.stderr


def test_a_free_joint_is_not_added_to_a_urdf_rooted_at_world_as_the_reference_does(cli, tmp_path):
    """The reference's -f says "Not adding a free joint because world is the URDF root"; each
    body the world held fixed got a free joint of its own, and a sensor frame fell away."""
    urdf = two_link_urdf(
        extra='<link name="world"/><joint name="w" type="fixed"><parent link="world"/>'
        '<child link="base"/></joint><link name="lidar"/><joint name="l" type="fixed">'
        '<parent link="world"/><child link="lidar"/><origin xyz="1 0 0.5"/></joint>'
    )
    write(tmp_path / "robot.urdf", urdf)
    result = cli("convert", "-u", "robot.urdf", "-o", "out", "-f", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert "-f: not adding a free joint, because world is the URDF's root" in result.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "scene.xml"))
    assert model.nq == 1  # the hinge alone
    text = cli("convert", "-r", urdf, "-o", "out2", "-f", cwd=tmp_path)
    assert text.code == EXIT_OK and "not adding a free joint" in text.stderr


def test_publish_topic_says_ros_is_needed(cli, tmp_path):
    result = cli("convert", "-u", "x.urdf", "-p", "/mujoco_robot_description", cwd=tmp_path)
    assert result.code == EXIT_USAGE
    assert "needs ROS" in result.stderr and "-o DIR" in result.stderr


def test_bad_package_argument(cli, tmp_path):
    result = cli("convert", "-u", "x.urdf", "--package", "nodir", cwd=tmp_path)
    assert result.code == EXIT_USAGE
    assert "is not NAME=DIR" in result.stderr


def test_custom_scene_file_is_used(cli, tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    scene = write(
        tmp_path / "my_scene.xml",
        '<mujoco><include file="mujoco_description_formatted.xml"/><option timestep="0.001"/></mujoco>',
    )
    result = cli("convert", "-u", "robot.urdf", "-o", "out", "--scene", str(scene), cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert (tmp_path / "out" / "scene.xml").read_text() == scene.read_text()


def test_an_unknown_package_is_added_with_the_package_flag(cli, tmp_path):
    urdf = two_link_urdf().replace(
        '<geometry><box size="0.2 0.2 0.1"/></geometry>',
        '<geometry><mesh filename="package://base_pkg/meshes/base.stl"/></geometry>',
    )
    write(tmp_path / "robot.urdf", urdf)
    result = cli("convert", "-u", "robot.urdf", "-o", "out", cwd=tmp_path)
    assert result.code == 4, result.stderr
    assert "pass --package base_pkg=<folder>" in result.stderr
    assert "robot.yaml" not in result.stderr


def test_asset_dir_reads_pre_generated_obj_meshes(cli, tmp_path):
    """-a: the reference converter's folder of pre-generated OBJ meshes (assets/full/<stem>/)."""
    from tests.meshes.samples import ascii_stl

    (tmp_path / "meshes").mkdir()
    ascii_stl(tmp_path / "meshes" / "base.stl")
    urdf = two_link_urdf().replace(
        '<geometry><box size="0.2 0.2 0.1"/></geometry>',
        '<geometry><mesh filename="meshes/base.stl"/></geometry>',
    )
    write(tmp_path / "robot.urdf", urdf)
    # A pre-generated mesh unlike the STL: a tetrahedron far from the origin.
    write(
        tmp_path / "previous" / "assets" / "full" / "base" / "base.obj",
        "v 5 5 5\nv 6 5 5\nv 5 6 5\nv 5 5 6\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    plain = cli("convert", "-u", "robot.urdf", "-o", "plain", cwd=tmp_path)
    assert plain.code == EXIT_OK, plain.stderr
    reused = cli("convert", "-u", "robot.urdf", "-o", "reused", "-a", "previous", cwd=tmp_path)
    assert reused.code == EXIT_OK, reused.stderr
    for folder, tetrahedron in (("plain", False), ("reused", True)):
        model = mujoco.MjModel.from_xml_path(str(tmp_path / folder / "scene.xml"))
        assert (4 in model.mesh_vertnum.tolist()) is tetrahedron, folder
    missing = cli("convert", "-u", "robot.urdf", "-o", "x", "-a", "nowhere", cwd=tmp_path)
    assert missing.code == EXIT_USAGE and "not a folder" in missing.stderr


def test_asset_dir_keeps_the_colour_of_a_dae_its_obj_stands_for(cli, tmp_path):
    """An OBJ of an earlier run carries no colour of its own (mjcfbuild's own output keeps it
    in the model's <material>, the reference converter's in obj2mjcf's XML): it takes the
    colour of the DAE it stands for, which it lost before."""
    from tests.meshes.test_collada_looks import coloured_dae

    (tmp_path / "meshes").mkdir()
    coloured_dae(tmp_path / "meshes" / "base.dae", "0.9 0.1 0.1")
    urdf = two_link_urdf().replace(
        '<collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>',
        '<visual><geometry><mesh filename="meshes/base.dae"/></geometry></visual>',
    )
    write(tmp_path / "robot.urdf", urdf)
    # the reference converter's layout, its OBJ without a material library
    write(
        tmp_path / "previous" / "assets" / "full" / "base" / "base.obj",
        "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    plain = cli("convert", "-u", "robot.urdf", "-o", "plain", cwd=tmp_path)
    assert plain.code == EXIT_OK, plain.stderr
    for earlier in ("previous", "plain"):  # the reference's folder, mjcfbuild's own
        out = f"from_{earlier}"
        reused = cli("convert", "-u", "robot.urdf", "-o", out, "-a", earlier, cwd=tmp_path)
        assert reused.code == EXIT_OK, reused.stderr
        model = mujoco.MjModel.from_xml_path(str(tmp_path / out / "scene.xml"))
        rgbas = [[round(float(v), 3) for v in model.mat_rgba[k]] for k in range(model.nmat)]
        assert [0.9, 0.1, 0.1, 1.0] in rgbas, (earlier, rgbas)


def test_help_says_what_each_reference_flag_does(cli):
    text = " ".join(cli("convert", "--help").stdout.split()).split("options:", 1)[1]
    for flag in ("--convert_stl_to_obj", "--save_only", "--use_collision_tags"):
        after = text.split(flag, 1)[1][:200]
        assert "no effect" in after and "always" in after, flag
    assert "pre-generated OBJ meshes" in text.split("--asset_dir", 1)[1][:200]


_PROBE = (
    "import sys\n"
    "from mjcfbuild.cli import run\n"
    "code = run(sys.argv[1:])\n"
    "print('imported:', ','.join(sorted(m for m in sys.modules if m.split('.')[0] in "
    "('doit', 'pydantic', 'yaml', 'numpy', 'mujoco', 'trimesh', 'lxml', 'xacro', 'fsspec')"
    " or m.startswith(('mjcfbuild.engine.', 'mjcfbuild.manifest')) "
    "and m != 'mjcfbuild.engine.stamp')))\n"
    "sys.exit(code)\n"
)


def _convert_in_probe(cwd, *argv):
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, "-c", _PROBE, "convert", *argv], cwd=cwd, capture_output=True, text=True
    )
    [imported] = [line for line in done.stdout.splitlines() if line.startswith("imported:")]
    return done, imported.removeprefix("imported:").strip()


def test_a_convert_no_op_takes_builds_fast_path_and_imports_nothing_heavy(cli, arm, tmp_path):
    argv = ["-u", str(arm / "urdf" / "arm.urdf.xacro"), "--package", f"arm_description={arm}"]
    argv += ["-o", "out", "with_camera:=true"]
    first = cli("convert", *argv, cwd=tmp_path)
    assert first.code == EXIT_OK, first.stderr
    done, imported = _convert_in_probe(tmp_path, *argv)
    assert done.returncode == 0, done.stderr
    assert "0 run," in done.stdout and imported == ""
    # Another argument, or an edited input, is another build: the full path decides.
    done, imported = _convert_in_probe(tmp_path, *argv[:-1], "with_camera:=false")
    assert done.returncode == 0, done.stderr
    assert "doit" in imported and "up to date" in done.stdout
    finger = arm / "urdf" / "finger.xacro"
    finger.write_text(finger.read_text() + "\n<!-- edited -->\n")
    done, imported = _convert_in_probe(tmp_path, *argv)
    assert done.returncode == 0, done.stderr
    assert "doit" in imported


def test_a_description_piped_in_is_built_and_an_empty_pipe_is_named_as_stdin(tmp_path):
    from mjcfbuild.errors import EXIT_INPUT
    from tests.conftest import run_cli

    done = run_cli("convert", "-r", "-", "-o", "out", cwd=tmp_path, stdin=two_link_urdf())
    assert done.code == EXIT_OK, done.stderr
    assert (tmp_path / "out" / "mujoco_description_formatted.xml").is_file()
    empty = run_cli("convert", "-r", "-", "-o", "out", cwd=tmp_path, stdin="")
    assert empty.code == EXIT_INPUT
    assert empty.stderr.startswith(
        "mjcfbuild: error: <stdin>: the robot description read from standard input is empty"
    )


def test_xacro_arguments_are_read_as_the_xacro_command_reads_them():
    """Stripped, an empty value leaves the default (a launch file's empty argument), a ROS 1
    private parameter (_name) is no argument; a word that is no NAME:=VALUE is refused."""
    import pytest

    from mjcfbuild.cli.convert import parse_xacro_args
    from mjcfbuild.errors import UsageError

    given = ["prefix:=", " side := left ", "_foo:=1", "__dunder:=2", "count:=3"]
    assert parse_xacro_args(given) == {"side": "left", "__dunder": "2", "count": "3"}
    with pytest.raises(UsageError):
        parse_xacro_args(["a:=b:=c"])


def test_write_errors_suggest_the_o_flag_not_robot_yamls_output_folder():
    from mjcfbuild.cli.convert import command_line_hint

    assert command_line_hint("check its permissions, or set output.folder") == (
        "check its permissions, or choose another -o"
    )
    assert "output.folder" not in command_line_hint(
        "move it out of the folder (or remove it), or set output.folder to a folder of the "
        "build's own"
    )
    assert "-o" in command_line_hint(
        "remove the link and let the build make the folder, or set output.folder to the folder "
        "it points at"
    )


def test_a_yaml_file_given_as_a_xacro_argument_value_is_no_manifest():
    from mjcfbuild.cli.convert import manifest_given

    assert manifest_given(["-u", "r.urdf.xacro", "config:=robot.yaml", "--scene", "s.yaml"]) is None
    assert manifest_given(["-u", "r.urdf", "x.yml"]) is not None
