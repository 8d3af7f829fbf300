"""A small quadruped URDF for the motor tests: a box trunk and four three-joint legs."""

from __future__ import annotations

LEGS = {"FL": (0.18, 0.1), "FR": (0.18, -0.1), "RL": (-0.18, 0.1), "RR": (-0.18, -0.1)}


def _inertial(mass: float, ixx: float, iyy: float, izz: float, z: float = 0.0) -> str:
    return (
        f'<inertial><origin xyz="0 0 {z}"/><mass value="{mass}"/>'
        f'<inertia ixx="{ixx}" iyy="{iyy}" izz="{izz}" ixy="0" ixz="0" iyz="0"/></inertial>'
    )


def _leg(name: str, x: float, y: float, transmission: float | None) -> str:
    calf = (
        f'<link name="{name}_hip">{_inertial(0.6, 4e-4, 6e-4, 4e-4)}'
        f'<collision><geometry><sphere radius="0.03"/></geometry></collision></link>'
        f'<link name="{name}_thigh">{_inertial(0.9, 5e-3, 5e-3, 6e-4, -0.1)}'
        f'<collision><origin xyz="0 0 -0.1"/><geometry><box size="0.03 0.03 0.2"/></geometry>'
        f"</collision></link>"
        f'<link name="{name}_calf">{_inertial(0.15, 2e-3, 2e-3, 2e-5, -0.1)}'
        f'<collision><origin xyz="0 0 -0.1"/><geometry><box size="0.02 0.02 0.2"/></geometry>'
        f"</collision>"
        f'<collision><origin xyz="0 0 -0.2"/><geometry><sphere radius="0.02"/></geometry>'
        f"</collision></link>"
        f'<joint name="{name}_hip_joint" type="revolute"><parent link="trunk"/>'
        f'<child link="{name}_hip"/><origin xyz="{x} {y} 0"/><axis xyz="1 0 0"/>'
        f'<limit lower="-0.8" upper="0.8" effort="23.7" velocity="30.1"/></joint>'
        f'<joint name="{name}_thigh_joint" type="revolute"><parent link="{name}_hip"/>'
        f'<child link="{name}_thigh"/><origin xyz="0 {0.08 if y > 0 else -0.08} 0"/>'
        f'<axis xyz="0 1 0"/><limit lower="-1.5" upper="3.4" effort="23.7" velocity="30.1"/>'
        f"</joint>"
        f'<joint name="{name}_calf_joint" type="revolute"><parent link="{name}_thigh"/>'
        f'<child link="{name}_calf"/><origin xyz="0 0 -0.2"/><axis xyz="0 1 0"/>'
        f'<limit lower="-2.7" upper="-0.9" effort="35.55" velocity="20.06"/></joint>'
    )
    if transmission is not None:
        calf += (
            f'<transmission name="{name}_calf_tran"><type>transmission_interface/'
            f'SimpleTransmission</type><joint name="{name}_calf_joint"><hardwareInterface>'
            f"hardware_interface/EffortJointInterface</hardwareInterface></joint>"
            f'<actuator name="{name}_calf_motor"><mechanicalReduction>{transmission}'
            f"</mechanicalReduction></actuator></transmission>"
        )
    return calf


def quadruped_urdf(transmission: float | None = None) -> str:
    """The quadruped; ``transmission``: a ROS 1 <transmission> reduction on every calf."""
    legs = "".join(_leg(name, x, y, transmission) for name, (x, y) in LEGS.items())
    return f"""<?xml version="1.0" encoding="utf-8"?>
<robot name="quad">
  <link name="trunk">{_inertial(5.0, 0.02, 0.06, 0.07)}
    <collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision>
  </link>
  {legs}
</robot>
"""


MANIFEST = """name: quad
source: {urdf: robot.urdf}
options: {free_joint: true}
home: {"*_thigh_joint": 0.9, "*_calf_joint": -1.8}
"""
