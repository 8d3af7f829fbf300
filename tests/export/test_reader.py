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


# Each joint's speed limit from what drives it: a <dcmotor> position servo behind a 2:1 gear
# (no-load speed 7 rad/s at the motor), a <dcmotor> on a voltage input (at most 6 V of a 12 V
# motor: half its 5 rad/s), a velocity servo, an unlimited hinge on a velocity servo behind a
# 4:1 gear, a position servo (no speed limit known) and a coupled joint without an actuator
# (its leader's speed times the multiplier).
DRIVEN = """<mujoco model="driven">
  <compiler angle="radian"/>
  <option gravity="0 0 0"/>
  <worldbody>
    <body name="base">
      <geom type="box" size="0.1 0.1 0.05"/>
      <body name="a" pos="0 0 0.1">
        <joint name="dc" axis="0 1 0" range="-1 1"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.02"/>
      </body>
      <body name="b" pos="0.2 0 0.1">
        <joint name="dc_voltage" axis="0 1 0" range="-1 1"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.02"/>
      </body>
      <body name="c" pos="0.4 0 0.1">
        <joint name="servo" type="slide" axis="0 0 1" range="-0.1 0.1"/>
        <geom type="box" size="0.02 0.02 0.02"/>
      </body>
      <body name="d" pos="0.6 0 0.1">
        <joint name="wheel" axis="0 1 0"/>
        <geom type="cylinder" size="0.05 0.01"/>
      </body>
      <body name="e" pos="0.8 0 0.1">
        <joint name="held" axis="0 1 0" range="-1 1"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.02"/>
      </body>
      <body name="f" pos="1 0 0.1">
        <joint name="coupled" type="slide" axis="1 0 0" range="-0.2 0.2"/>
        <geom type="box" size="0.02 0.02 0.02"/>
      </body>
    </body>
  </worldbody>
  <equality>
    <joint joint1="coupled" joint2="servo" polycoef="0 -0.5 0 0 0"/>
  </equality>
  <actuator>
    <dcmotor name="dc" joint="dc" input="pos" nominal="24 3 7" controller="10 0 1 0 0 24"
             saturation="2.5 0 0" gear="2" ctrlrange="-1 1"/>
    <dcmotor name="dc_voltage" joint="dc_voltage" input="voltage" nominal="12 2 5"
             ctrlrange="-6 6"/>
    <velocity name="servo" joint="servo" kv="50" ctrlrange="-0.3 0.4"/>
    <velocity name="wheel" joint="wheel" kv="1" ctrlrange="-20 20" gear="4"/>
    <position name="held" joint="held" kp="100" ctrlrange="-1 1"/>
  </actuator>
</mujoco>
"""


@pytest.fixture(scope="module")
def driven(tmp_path_factory):
    path = tmp_path_factory.mktemp("driven") / "driven.xml"
    path.write_text(DRIVEN)
    return path


def _limits(urdf: bytes) -> dict[str, dict[str, str]]:
    root = etree.fromstring(urdf)
    return {
        joint.get("name"): dict(joint.find("limit").attrib)
        for joint in root.iter("joint")
        if joint.find("limit") is not None
    }


def test_speed_limits_are_where_the_drives_stop_pushing(driven):
    """Each exported velocity is the speed at which MuJoCo's actuator, commanded as hard as it
    can be, stops pushing the joint: its force is zero there, still pushing just below, and
    braking just above."""
    result = export_urdf(driven, ExportOptions(sites=False))
    limits = _limits(result.urdf)
    velocity = {name: float(limit["velocity"]) for name, limit in limits.items()}
    assert velocity == pytest.approx(
        {"dc": 3.5, "dc_voltage": 2.5, "servo": 0.4, "wheel": 5.0, "held": 0.0, "coupled": 0.2}
    )
    assert limits["wheel"] == {"effort": "0", "velocity": "5"}  # continuous: speed, no range
    model = mujoco.MjModel.from_xml_path(str(driven))
    data = mujoco.MjData(model)
    for name in ("dc", "dc_voltage", "servo", "wheel"):
        actuator, joint = model.actuator(name), model.joint(name)
        command = model.actuator_ctrlrange[actuator.id].max()  # as fast / as far as allowed
        forces = []
        for scale in (0.99, 1.0, 1.01):
            mujoco.mj_resetData(model, data)
            data.ctrl[actuator.id] = command
            data.qvel[joint.dofadr[0]] = scale * velocity[name]
            mujoco.mj_forward(model, data)
            forces.append(float(data.qfrc_actuator[joint.dofadr[0]]))
        assert forces[0] > 0 and abs(forces[1]) < 1e-9 and forces[2] < 0, (name, forces)
    assert any(
        "no speed limit known for 1 joint(s) (held)" in warning for warning in result.warnings
    )


def test_a_dcmotors_effort_is_what_it_gives_standing_still(driven):
    """A <dcmotor>'s effort is its stall torque at its top voltage, capped by its saturation,
    times the gear: what MuJoCo's actuator gives the joint at rest under the full command."""
    limits = _limits(export_urdf(driven, ExportOptions(sites=False)).urdf)
    model = mujoco.MjModel.from_xml_path(str(driven))
    data = mujoco.MjData(model)
    for name, expected in (("dc", 5.0), ("dc_voltage", 1.0)):  # saturation 2.5 x 2; 6 V of 12
        actuator = model.actuator(name)
        mujoco.mj_resetData(model, data)
        data.ctrl[actuator.id] = model.actuator_ctrlrange[actuator.id].max()
        mujoco.mj_forward(model, data)
        force = abs(float(data.qfrc_actuator[model.joint(name).dofadr[0]]))
        assert force == pytest.approx(expected, rel=1e-9)
        assert float(limits[name]["effort"]) == pytest.approx(force, rel=1e-9), name


def test_speeds_known_beyond_the_model_fill_in_and_never_overrule_it(driven):
    """A build's own knowledge (a drive, the source URDF's limit) gives the joints the model
    leaves without a speed theirs; the model's actuators still decide the others."""
    speeds = {"held": 1.5, "servo": 9.0, "dc": 0.0}
    result = export_urdf(driven, ExportOptions(sites=False), speeds)
    velocity = {name: float(limit["velocity"]) for name, limit in _limits(result.urdf).items()}
    assert velocity["held"] == 1.5
    assert velocity["servo"] == pytest.approx(0.4)
    assert velocity["dc"] == pytest.approx(3.5)
    assert not any("no speed limit known" in warning for warning in result.warnings)
