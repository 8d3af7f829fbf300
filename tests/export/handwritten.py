"""A hand-written MJCF with everything export-urdf has to map: capsules, two joints in one
body away from its origin, a slide, an unlimited hinge, a ball, a coupling, a mesh drawn in two
colours, an ellipsoid, visual-only and collision-only geoms, and sites."""

from __future__ import annotations

from pathlib import Path

MODEL = """<mujoco model="handwritten">
  <compiler angle="radian"/>
  <default>
    <default class="visual"><geom contype="0" conaffinity="0" group="2"/></default>
    <default class="collision"><geom group="3"/></default>
  </default>
  <asset>
    <mesh name="part" file="part.obj" scale="1 1 2"/>
    <material name="steel" rgba="0.6 0.6 0.65 1"/>
  </asset>
  <worldbody>
    <body name="base" pos="0 0 0.5" quat="0.9238795 0 0 0.3826834">
      <geom type="box" size="0.1 0.1 0.05" rgba="0.2 0.2 0.2 1"/>
      <site name="base_imu" pos="0.02 0 0.03" quat="0.7071068 0.7071068 0 0"/>
      <body name="arm" pos="0 0 0.1" euler="0.2 0 0">
        <joint name="yaw" type="hinge" axis="0 0 1" pos="0.01 0 0" range="-2 2"/>
        <joint name="pitch" type="hinge" axis="0 1 0" pos="0 0.02 0.05" range="-1 1.5"/>
        <geom class="visual" type="capsule" fromto="0 0 0 0 0 0.3" size="0.03"/>
        <geom class="collision" type="capsule" fromto="0 0 0 0 0 0.3" size="0.035"/>
        <body name="slider" pos="0 0 0.3">
          <joint name="extend" type="slide" axis="0.6 0 0.8" range="-0.05 0.1"/>
          <geom type="mesh" mesh="part" material="steel" pos="0 0 0.05"/>
          <geom class="visual" type="mesh" mesh="part" rgba="0.9 0.1 0.1 1" pos="0 0.06 0"/>
          <body name="wheel" pos="0.05 0 0.1" euler="0 1.5707963 0">
            <joint name="spin" type="hinge" axis="0 0 1"/>
            <geom type="cylinder" size="0.04 0.01" rgba="0.1 0.1 0.9 1"/>
            <geom class="visual" type="ellipsoid" size="0.02 0.03 0.015" pos="0 0 0.02"/>
          </body>
          <body name="wrist" pos="0 0 0.12">
            <joint name="wrist_ball" type="ball"/>
            <geom type="sphere" size="0.02"/>
            <site name="tool" pos="0 0 0.04"/>
            <body name="finger_a" pos="0.01 0 0.03">
              <joint name="finger_a" type="slide" axis="1 0 0" range="0 0.02"/>
              <geom type="box" size="0.005 0.005 0.02"/>
            </body>
            <body name="finger_b" pos="-0.01 0 0.03">
              <joint name="finger_b" type="slide" axis="-1 0 0" range="0 0.02"/>
              <geom type="box" size="0.005 0.005 0.02"/>
            </body>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <equality>
    <joint joint1="finger_b" joint2="finger_a" polycoef="0.001 1 0 0 0"/>
  </equality>
</mujoco>
"""

BOX_OBJ = """v -0.02 -0.02 -0.02
v 0.02 -0.02 -0.02
v 0.02 0.02 -0.02
v -0.02 0.02 -0.02
v -0.02 -0.02 0.02
v 0.02 -0.02 0.02
v 0.02 0.02 0.02
v -0.02 0.02 0.02
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""


def write_model(folder: Path) -> Path:
    """The model and its mesh in ``folder``; the model's path."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "part.obj").write_text(BOX_OBJ)
    path = folder / "handwritten.xml"
    path.write_text(MODEL)
    return path
