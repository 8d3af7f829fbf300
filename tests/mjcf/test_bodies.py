"""Which links become bodies, where fused links and shapes end up, combined masses."""

from __future__ import annotations

import pytest

from mjcfbuild.mjcf.bodies import build_bodies
from mjcfbuild.urdf.parse import parse_urdf

FUSED = """<robot name="r">
  <link name="base"><inertial><origin xyz="0 0 0"/><mass value="2"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="plate"><inertial><origin xyz="0 0 0"/><mass value="2"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0 0 0.1"/><geometry><box size="1 1 1"/></geometry></visual></link>
  <link name="tip"/>
  <joint name="f" type="fixed"><parent link="base"/><child link="plate"/><origin xyz="1 0 0"/></joint>
  <joint name="m" type="revolute"><parent link="plate"/><child link="tip"/><origin xyz="0 1 0"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def test_fusing_moves_shapes_links_and_children_into_the_parent_body():
    bodies = build_bodies(parse_urdf(FUSED.encode()), fuse_static=True)
    assert [b.name for b in bodies] == ["base", "tip"]
    base, tip = bodies
    assert [(f.link, f.fused) for f in base.links] == [("base", False), ("plate", True)]
    assert base.shapes[0].pose.position == (1.0, 0.0, 0.1)
    assert tip.parent == "base" and tip.pose.position == (1.0, 1.0, 0.0)


def test_fused_masses_combine_with_the_parallel_axis_theorem():
    base = build_bodies(parse_urdf(FUSED.encode()), fuse_static=True)[0]
    assert base.mass.mass == 4
    assert base.mass.com == (0.5, 0.0, 0.0)
    # each 2 kg part sits 0.5 m from the combined centre along x: +2*0.25 about y and z
    assert base.mass.inertia[0][0] == pytest.approx(2.0)
    assert base.mass.inertia[1][1] == pytest.approx(3.0)
    assert base.mass.inertia[2][2] == pytest.approx(3.0)


def test_without_fusing_every_link_is_a_body():
    bodies = build_bodies(parse_urdf(FUSED.encode()), fuse_static=False)
    assert [b.name for b in bodies] == ["base", "plate", "tip"]
    assert bodies[1].joint.kind == "fixed" and not bodies[1].moves


def test_a_chain_thousands_of_links_deep_builds_without_recursion():
    from bench.deep_chain import snake_urdf

    robot = parse_urdf(snake_urdf(2500, fixed_every=2).encode())
    bodies = build_bodies(robot, fuse_static=False)
    assert [b.name for b in bodies] == [f"l{i}" for i in range(2500)]
    assert all(b.parent == f"l{i}" for i, b in enumerate(bodies[1:]))
    fused = build_bodies(robot, fuse_static=True)
    # Joints j2, j4, ... are fixed: l2 is fused into l1's body, l4 into l3's, and so on.
    assert [b.name for b in fused] == ["l0", *(f"l{i}" for i in range(1, 2500, 2))]
    pair = fused[-2]
    assert [(f.link, f.fused) for f in pair.links] == [("l2497", False), ("l2498", True)]
    assert pair.links[1].pose.position == pytest.approx((0.05, 0.0, 0.0))
    assert pair.parent == "l2495" and pair.mass is not None and pair.mass.mass == 0.1
    assert fused[-1].parent == "l2497"


WORLD_HOLDS_TWO = """<robot name="r">
  <link name="world"/>
  <link name="mount"><inertial><mass value="0.1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="base"><inertial><mass value="2"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><mass value="1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="rail"/>
  <joint name="wm" type="fixed"><parent link="world"/><child link="mount"/>
    <origin xyz="1 0 1"/></joint>
  <joint name="wb" type="fixed"><parent link="world"/><child link="base"/>
    <origin xyz="0 0 0.5" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="wr" type="prismatic"><parent link="world"/><child link="rail"/>
    <origin xyz="0 2 0"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


@pytest.mark.parametrize("fuse_static", [True, False])
def test_floating_a_world_rooted_robot_floats_what_the_world_holds_as_one_whole(fuse_static):
    # free_joint on a URDF bolted to `world`: the heaviest link the world holds fixed (base, not
    # the mount listed first) floats, and the mount and the rail hang from it where the URDF
    # puts them, so that neither floats away (or falls) on its own.
    bodies = build_bodies(
        parse_urdf(WORLD_HOLDS_TWO.encode()), fuse_static=fuse_static, free_joint=True
    )
    by_name = {body.name: body for body in bodies}
    assert by_name["base"].parent == "world" and by_name["base"].pose.position == (0, 0, 0.5)
    assert by_name["rail"].parent == "base" and by_name["rail"].joint.name == "wr"
    assert by_name["rail"].pose.position == pytest.approx((2.0, 0.0, -0.5))
    if fuse_static:
        mount = next(frame for frame in by_name["base"].links if frame.link == "mount")
        assert mount.fused and mount.pose.position == pytest.approx((0.0, -1.0, 0.5))
    else:
        assert by_name["mount"].parent == "base" and not by_name["mount"].moves
        assert by_name["mount"].pose.position == pytest.approx((0.0, -1.0, 0.5))
    assert [body.name for body in bodies if body.parent == "world"] == ["base"]


def test_a_urdf_floating_joint_keeps_what_the_world_holds_beside_it_bolted():
    # The URDF floats its robot itself: free_joint adds no free joint, and a mount the world
    # holds beside it stays in the world (a free joint only joins a body to the world).
    urdf = WORLD_HOLDS_TWO.replace(
        '<joint name="wb" type="fixed">', '<joint name="wb" type="floating">'
    )
    bodies = build_bodies(parse_urdf(urdf.encode()), fuse_static=False, free_joint=True)
    by_name = {body.name: body for body in bodies}
    assert not any(body.floating for body in bodies)
    assert by_name["base"].parent == "world" and by_name["mount"].parent == "world"
