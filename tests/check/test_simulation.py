"""The zero-control simulation: MuJoCo's warnings name the joint where the state ran away."""

from __future__ import annotations

import mujoco

from mjcfbuild.check.simulation import dof_joint, simulate

RUNAWAY = """<mujoco><worldbody><body name="base"><freejoint name="float"/>
  <geom size="0.1" mass="1"/>
  <body name="arm"><joint name="{joint}" type="hinge" stiffness="1e20" springref="1"/>
    <geom type="capsule" fromto="0 0 0 0 0 0.5" size="0.02" mass="0.1"/></body>
</body></worldbody></mujoco>"""


def test_an_unstable_acceleration_names_its_joint_not_a_dof_index():
    # scikit-robot's r8_6.urdf stopped with "badqacc (x1, last info 0)": an index, nothing more
    fixed = RUNAWAY.format(joint="elbow").replace('<freejoint name="float"/>', "")
    result = simulate(mujoco.MjModel.from_xml_string(fixed), steps=5)
    assert not result.passes
    assert result.warnings == ["badqacc (x1, last at joint 'elbow')"]


def test_on_a_floating_base_the_base_is_not_named_as_the_culprit():
    # MuJoCo records the base's DOF 0 whichever joint ran away (r8_6 with free_joint: true).
    result = simulate(mujoco.MjModel.from_xml_string(RUNAWAY.format(joint="elbow")), steps=5)
    assert not result.passes
    (warning,) = result.warnings
    assert "floating base 'float'" in warning and "last at joint" not in warning, warning


def test_a_dof_names_its_joint():
    model = mujoco.MjModel.from_xml_string(RUNAWAY.format(joint="elbow"))
    assert [dof_joint(model, dof) for dof in range(model.nv)] == ["float"] * 6 + ["elbow"]
    assert dof_joint(model, model.nv) is None and dof_joint(model, -1) is None
