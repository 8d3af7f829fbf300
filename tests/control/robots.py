"""Small generated robots (primitives only) for the standing, wheel and gain tests."""

from __future__ import annotations


def inertial(mass: float, xyz: str = "0 0 0", moment: float | None = None) -> str:
    """An <inertial> of ``mass`` at ``xyz`` with equal principal moments."""
    moment = moment if moment is not None else max(mass * 0.002, 1e-5)
    return (
        f'<inertial><origin xyz="{xyz}"/><mass value="{mass}"/>'
        f'<inertia ixx="{moment}" iyy="{moment}" izz="{moment}" ixy="0" ixz="0" iyz="0"/>'
        "</inertial>"
    )


def quadruped(joint_type: str = "revolute", foot_offset: float = 0.0) -> str:
    """A 6 kg quadruped: a box trunk, legs of hip (x), thigh and calf (y) joints, sphere feet.
    At zero its legs are straight; ``foot_offset`` (m) bends each calf forward at the knee
    so the feet sit that far ahead of the hips."""
    legs = []
    for name, x, y in (
        ("FL", 0.18, 0.1),
        ("FR", 0.18, -0.1),
        ("RL", -0.18, 0.1),
        ("RR", -0.18, -0.1),
    ):
        limit = '<limit lower="-2.5" upper="2.5" effort="30" velocity="20"/>'
        if joint_type == "continuous":
            limit = '<limit effort="30" velocity="20"/>'
        legs.append(
            f"""
  <link name="{name}_hip">{inertial(0.3)}</link>
  <link name="{name}_thigh">{inertial(0.4, "0 0 -0.1")}
    <collision><origin xyz="0 0 -0.1"/><geometry><cylinder radius="0.015" length="0.2"/></geometry></collision></link>
  <link name="{name}_calf">{inertial(0.15, f"{foot_offset / 2} 0 -0.1")}
    <collision><origin xyz="{foot_offset} 0 -0.2"/><geometry><sphere radius="0.02"/></geometry></collision></link>
  <joint name="{name}_hip_joint" type="{joint_type}"><parent link="trunk"/><child link="{name}_hip"/>
    <origin xyz="{x} {y} 0"/><axis xyz="1 0 0"/>{limit}</joint>
  <joint name="{name}_thigh_joint" type="{joint_type}"><parent link="{name}_hip"/><child link="{name}_thigh"/>
    <origin xyz="0 0 0"/><axis xyz="0 1 0"/>{limit}</joint>
  <joint name="{name}_calf_joint" type="{joint_type}"><parent link="{name}_thigh"/><child link="{name}_calf"/>
    <origin xyz="0 0 -0.2"/><axis xyz="0 1 0"/>{limit}</joint>"""
        )
    return f"""<?xml version="1.0"?>
<robot name="quad">
  <link name="trunk">{inertial(4.0, moment=0.05)}
    <collision><geometry><box size="0.45 0.25 0.1"/></geometry></collision></link>
  {"".join(legs)}
</robot>
"""


def humanoid(torso_mass: float = 40.0, torso_height: float = 0.5) -> str:
    """A biped of box feet, straight legs and a heavy torso high above the hips: its centre of
    mass is over its feet at zero, and it stands only with weight-bearing gains."""
    legs = []
    for side, y in (("left", 0.1), ("right", -0.1)):
        legs.append(
            f"""
  <link name="{side}_hip">{inertial(1.0)}</link>
  <link name="{side}_thigh">{inertial(3.0, "0 0 -0.2", 0.03)}
    <collision><origin xyz="0 0 -0.2"/><geometry><cylinder radius="0.04" length="0.3"/></geometry></collision></link>
  <link name="{side}_shin">{inertial(2.0, "0 0 -0.2", 0.02)}
    <collision><origin xyz="0 0 -0.2"/><geometry><cylinder radius="0.035" length="0.3"/></geometry></collision></link>
  <link name="{side}_ankle">{inertial(0.3)}</link>
  <link name="{side}_foot">{inertial(0.6, "0.02 0 -0.05")}
    <collision><origin xyz="0.03 0 -0.05"/><geometry><box size="0.22 0.1 0.04"/></geometry></collision></link>
  <joint name="{side}_hip_pitch" type="revolute"><parent link="pelvis"/><child link="{side}_hip"/>
    <origin xyz="0 {y} 0"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="300" velocity="10"/></joint>
  <joint name="{side}_hip_roll" type="revolute"><parent link="{side}_hip"/><child link="{side}_thigh"/>
    <axis xyz="1 0 0"/><limit lower="-0.5" upper="0.5" effort="300" velocity="10"/></joint>
  <joint name="{side}_knee" type="revolute"><parent link="{side}_thigh"/><child link="{side}_shin"/>
    <origin xyz="0 0 -0.4"/><axis xyz="0 1 0"/><limit lower="0" upper="2.5" effort="300" velocity="10"/></joint>
  <joint name="{side}_ankle_pitch" type="revolute"><parent link="{side}_shin"/><child link="{side}_ankle"/>
    <origin xyz="0 0 -0.4"/><axis xyz="0 1 0"/><limit lower="-0.8" upper="0.8" effort="300" velocity="10"/></joint>
  <joint name="{side}_ankle_roll" type="revolute"><parent link="{side}_ankle"/><child link="{side}_foot"/>
    <axis xyz="1 0 0"/><limit lower="-0.4" upper="0.4" effort="300" velocity="10"/></joint>"""
        )
    return f"""<?xml version="1.0"?>
<robot name="biped">
  <link name="pelvis">{inertial(5.0, moment=0.05)}
    <collision><geometry><box size="0.15 0.3 0.1"/></geometry></collision></link>
  <link name="torso">{inertial(torso_mass, f"0 0 {torso_height}", 1.0)}
    <collision><origin xyz="0 0 {torso_height}"/><geometry><box size="0.2 0.3 0.4"/></geometry></collision></link>
  <joint name="waist" type="fixed"><parent link="pelvis"/><child link="torso"/></joint>
  {"".join(legs)}
</robot>
"""


def rover(arm_joint: str = "continuous") -> str:
    """A base on two wheels and a caster ball, with a one-link arm on a continuous joint: the
    wheels are continuous joints that roll on the floor, the arm's is not."""
    wheels = []
    for side, y in (("left", 0.2), ("right", -0.2)):
        wheels.append(
            f"""
  <link name="{side}_wheel">{inertial(0.5)}
    <collision><origin rpy="1.5707963267948966 0 0"/><geometry><cylinder radius="0.08" length="0.04"/></geometry></collision></link>
  <joint name="{side}_wheel_joint" type="continuous"><parent link="base"/><child link="{side}_wheel"/>
    <origin xyz="0.1 {y} 0"/><axis xyz="0 1 0"/><limit effort="10" velocity="10"/></joint>"""
        )
    return f"""<?xml version="1.0"?>
<robot name="rover">
  <link name="base">{inertial(8.0, moment=0.1)}
    <collision><origin xyz="0 0 0.03"/><geometry><box size="0.4 0.3 0.06"/></geometry></collision>
    <collision><origin xyz="-0.15 0 -0.05"/><geometry><sphere radius="0.03"/></geometry></collision></link>
  {"".join(wheels)}
  <link name="arm">{inertial(1.0, "0.2 0 0")}
    <collision><origin xyz="0.2 0 0" rpy="0 1.5707963267948966 0"/><geometry><cylinder radius="0.02" length="0.4"/></geometry></collision></link>
  <joint name="shoulder" type="{arm_joint}"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 1 0"/><limit effort="50" velocity="3"/></joint>
</robot>
"""


def drone() -> str:
    """A body with a floating joint to the world and nothing else."""
    return f"""<?xml version="1.0"?>
<robot name="drone">
  <link name="world"/>
  <link name="body">{inertial(1.2, moment=0.01)}
    <collision><geometry><box size="0.3 0.3 0.05"/></geometry></collision></link>
  <joint name="float" type="floating"><parent link="world"/><child link="body"/>
    <origin xyz="0 0 1"/></joint>
</robot>
"""


def gripper(followers: int = 4, finger_mass: float = 0.4) -> str:
    """A fixed gripper: a light leading slide and ``followers`` heavy fingers mimicking it."""
    fingers = []
    for index in range(followers):
        y = 0.03 * (index + 1)
        fingers.append(
            f"""
  <link name="finger{index}">{inertial(finger_mass, "0 0 0.03")}
    <collision><origin xyz="0 0 0.03"/><geometry><box size="0.01 0.01 0.06"/></geometry></collision></link>
  <joint name="finger{index}_joint" type="prismatic"><parent link="palm"/><child link="finger{index}"/>
    <origin xyz="0.05 {y} 0.02"/><axis xyz="0 0 1"/><limit lower="0" upper="0.04" effort="40" velocity="0.2"/>
    <mimic joint="lead" multiplier="1" offset="0"/></joint>"""
        )
    return f"""<?xml version="1.0"?>
<robot name="gripper">
  <link name="palm">{inertial(0.5)}
    <collision><geometry><box size="0.05 0.2 0.04"/></geometry></collision></link>
  <link name="lead_finger">{inertial(0.01, "0 0 0.03")}
    <collision><origin xyz="0 0 0.03"/><geometry><box size="0.01 0.01 0.06"/></geometry></collision></link>
  <joint name="lead" type="prismatic"><parent link="palm"/><child link="lead_finger"/>
    <origin xyz="-0.05 0 0.02"/><axis xyz="0 0 1"/><limit lower="0" upper="0.04" effort="40" velocity="0.2"/></joint>
  {"".join(fingers)}
</robot>
"""


def balancer() -> str:
    """A tall body on two wheels drawn as revolute joints without limits, and no caster:
    it balances only under a controller (Upkie and Cookie are drawn so)."""
    wheels = []
    for side, y in (("left", 0.12), ("right", -0.12)):
        wheels.append(
            f"""
  <link name="{side}_wheel">{inertial(0.3)}
    <collision><origin rpy="1.5707963267948966 0 0"/><geometry><cylinder radius="0.06" length="0.03"/></geometry></collision></link>
  <joint name="{side}_wheel_joint" type="revolute"><parent link="body"/><child link="{side}_wheel"/>
    <origin xyz="0 {y} 0"/><axis xyz="0 1 0"/><limit effort="5" velocity="20"/></joint>"""
        )
    return f"""<?xml version="1.0"?>
<robot name="balancer">
  <link name="body">{inertial(3.0, "0 0 0.25", 0.03)}
    <collision><origin xyz="0 0 0.25"/><geometry><box size="0.1 0.2 0.4"/></geometry></collision></link>
  {"".join(wheels)}
</robot>
"""


def planar_base() -> str:
    """A box moved in the plane by a URDF planar joint (three joints in MuJoCo)."""
    return f"""<?xml version="1.0"?>
<robot name="planar">
  <link name="base_footprint"/>
  <joint name="base_joint" type="planar"><parent link="base_footprint"/><child link="base_link"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/></joint>
  <link name="base_link">{inertial(5.0, moment=0.1)}
    <collision><geometry><box size="0.4 0.3 0.2"/></geometry></collision></link>
</robot>
"""
