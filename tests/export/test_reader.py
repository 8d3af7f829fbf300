"""What the export reads from a compiled model: couplings as MuJoCo enforces them (joints with
a nonzero ``ref`` included) and each joint's speed limit where the model knows it."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from lxml import etree

from mjcfbuild.export import ExportOptions, export_urdf

yourdfpy = pytest.importorskip("yourdfpy")

# Two couplings whose joints all have a nonzero ref: a hinge following a hinge and a slide
# following a slide. The old offset (c0 + c1 ref2 - ref1) put the follower 0.05 rad and 0.006 m
# away from where MuJoCo holds it.
COUPLED = """<mujoco model="coupled">
  <compiler angle="radian"/>
  <worldbody>
    <body name="base">
      <geom type="box" size="0.1 0.1 0.05"/>
      <body name="lead" pos="0 0 0.1">
        <joint name="lead" type="hinge" axis="0 1 0" ref="0.4" range="-1 1.5"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.02"/>
      </body>
      <body name="follow" pos="0.2 0 0.1" euler="0 0 0.3">
        <joint name="follow" type="hinge" axis="1 0 0" ref="-0.25"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.02"/>
      </body>
      <body name="push" pos="0 0.2 0.1">
        <joint name="push" type="slide" axis="0 0 1" ref="0.02" range="-0.05 0.1"/>
        <geom type="box" size="0.02 0.02 0.02"/>
      </body>
      <body name="pull" pos="0.2 0.2 0.1">
        <joint name="pull" type="slide" axis="1 0 0" ref="-0.01" range="-0.5 0.5"/>
        <geom type="box" size="0.02 0.02 0.02"/>
      </body>
    </body>
  </worldbody>
  <equality>
    <joint joint1="follow" joint2="lead" polycoef="0.1 -0.5 0 0 0"/>
    <joint joint1="pull" joint2="push" polycoef="0.005 2 0 0 0"/>
  </equality>
</mujoco>
"""


def _pose(data, body: str) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3] = data.body(body).xmat.reshape(3, 3)
    pose[:3, 3] = data.body(body).xpos
    return pose


def test_coupling_with_nonzero_ref_holds_mujocos_equality(tmp_path):
    """The exported mimic puts the follower where MuJoCo's equality holds it: set from the
    URDF's multiplier and offset, the equality's residual is 0, and an independent URDF reader
    (yourdfpy, which applies the mimic itself) places every link where MuJoCo does."""
    path = tmp_path / "coupled.xml"
    path.write_text(COUPLED)
    result = export_urdf(path, ExportOptions(sites=False))
    urdf_path = tmp_path / "coupled.urdf"
    urdf_path.write_bytes(result.urdf)
    root = etree.fromstring(result.urdf)
    mimics = {
        joint.get("name"): joint.find("mimic")
        for joint in root.iter("joint")
        if joint.find("mimic") is not None
    }
    assert sorted(mimics) == ["follow", "pull"]
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    names = ("lead", "follow", "push", "pull")
    refs = {name: float(model.qpos0[model.joint(name).qposadr[0]]) for name in names}
    assert all(abs(ref) > 0 for ref in refs.values())
    urdf = yourdfpy.URDF.load(str(urdf_path), build_scene_graph=True)
    assert sorted(urdf.actuated_joint_names) == ["lead", "push"]
    rng = np.random.default_rng(3)
    for _ in range(10):
        leaders = {"lead": float(rng.uniform(-1.4, 1.1)), "push": float(rng.uniform(-0.07, 0.08))}
        values = dict(leaders)
        for follower, mimic in mimics.items():
            leader = mimic.get("joint")
            values[follower] = float(mimic.get("multiplier")) * leaders[leader] + float(
                mimic.get("offset")
            )
        # An exported joint's zero is the pose its body is written in: MuJoCo's ref.
        for name, value in values.items():
            data.joint(name).qpos[0] = refs[name] + value
        mujoco.mj_forward(model, data)
        equality = data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY
        assert equality.sum() == 2
        assert np.abs(data.efc_pos[equality]).max() < 1e-9
        urdf.update_cfg(leaders)
        base = _pose(data, "base")
        for body in names:  # each body is named like its joint
            expected = np.linalg.inv(base) @ _pose(data, body)
            assert np.allclose(urdf.get_transform(body, "base"), expected, atol=1e-9), body
