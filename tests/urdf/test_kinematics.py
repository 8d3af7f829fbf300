"""Forward kinematics of a URDF, checked on chains whose answer is known by hand."""

from __future__ import annotations

import math

from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.parse import parse_urdf

CHAIN = """<robot name="chain">
  <link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/>
    <origin xyz="1 0 0"/><axis xyz="2 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j3" type="fixed"><parent link="c"/><child link="d"/>
    <origin xyz="0 0 0" rpy="0 0 1.5707963267948966"/></joint>
</robot>"""


def test_known_chain():
    robot = parse_urdf(CHAIN.encode())
    poses = link_poses(robot, {"j1": math.pi / 2, "j2": 0.5})
    # j1 turns the arm to point along +y; the slide of 0.5 adds to the 1 m offset.
    assert [round(v, 12) for v in poses["c"].position] == [0.0, 1.5, 1.0]
    # d is c turned by another quarter turn about z: its x axis points along -x.
    assert [round(poses["d"].rotation[i][0], 12) for i in range(3)] == [-1.0, 0.0, 0.0]


def test_zero_configuration_is_the_default():
    robot = parse_urdf(CHAIN.encode())
    assert [round(v, 12) for v in link_poses(robot)["c"].position] == [1.0, 0.0, 1.0]
