"""A pids_config_file read as ROS reads parameters: which PIDs mujoco_ros2_control finds."""

from __future__ import annotations

import pytest

from mjcfbuild.inputs.pid_gains import pids_file, read_pid_gains
from tests.conftest import write

HEAD = "mujoco_ros2_control_node:\n  ros__parameters:\n    pid_gains:\n      position:\n"


def test_gains_are_found_per_interface_and_joint_as_ros_types_them(tmp_path):
    path = write(
        tmp_path / "pids.yaml",
        HEAD + "        a: {p: 1e2, i: 0.0, d: 1.0e-3}\n"  # doubles to ROS (strings to YAML 1.1)
        "        b: {p: 100, i: 0.0, d: 1.0}\n"  # an integer: PidROS reads no gain
        "        c: {p: '1.0', i: 0.0, d: 1.0}\n"  # quoted: a string
        "        d: {p: 1.0, d: 1.0}\n",  # no i
    )
    gains = read_pid_gains(path)
    assert gains.defined == {("position", "a")}
    assert gains.faults == {
        ("position", "b"): "its p gain 100 is not a double (write 100.0)",
        ("position", "c"): "its p gain '1.0' is not a double (write a number)",
        ("position", "d"): "no i gain",
    }


@pytest.mark.parametrize("node", ["/**", "/robot/mujoco_ros2_control_node", "other_node"])
def test_only_parameters_of_the_runtimes_node_count(tmp_path, node):
    text = (
        HEAD.replace("mujoco_ros2_control_node:", f'"{node}":')
        + "        a: {p: 1.0, i: 0.0, d: 1.0}\n"
    )
    gains = read_pid_gains(write(tmp_path / "pids.yaml", text))
    assert gains.has("position", "a") == (node != "other_node")


def test_an_empty_file_defines_no_gains_and_broken_yaml_names_its_line(tmp_path):
    assert read_pid_gains(write(tmp_path / "empty.yaml", "")).defined == set()
    with pytest.raises(ValueError, match="line 2"):
        read_pid_gains(write(tmp_path / "bad.yaml", "a:\n  b: [1, 2\n"))


def test_only_an_absolute_path_names_a_file_here():
    assert pids_file({"pids_config_file": " /a/pids.yaml "}) is not None
    assert pids_file({"pids_config_file": "config/pids.yaml"}) is None
    assert pids_file({}) is None
