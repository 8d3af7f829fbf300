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


def test_convert_robot_description_string(cli, tmp_path):
    result = cli("convert", "-r", two_link_urdf(), "-o", "out", "-f", "--no-fuse", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "scene.xml"))
    assert model.nq == 8  # free joint + hinge


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
