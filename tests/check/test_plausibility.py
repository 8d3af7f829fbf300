"""The mesh plausibility test: each body's centre of mass inside its own geometry, visual and
collision geometry overlapping, a body that fails named with the likely cause."""

from __future__ import annotations

import json

import mujoco
import numpy as np
import trimesh

from mjcfbuild.check.plausibility import check_plausibility
from mjcfbuild.errors import EXIT_CHECK
from tests.conftest import run_cli, simple_manifest, write

# A hand-tuned model as MuJoCo Menagerie writes them: visual and collision classes, meshes and
# primitives, explicit inertials.
HAND_TUNED = """
<mujoco>
  <default>
    <default class="visual"><geom group="2" contype="0" conaffinity="0"/></default>
    <default class="collision"><geom group="3"/></default>
  </default>
  <asset>
    <mesh name="shell" vertex="{shell}"/>
  </asset>
  <worldbody>
    <body name="base" pos="0 0 0.5">
      <inertial pos="0 0 0" mass="2" diaginertia="0.01 0.01 0.01"/>
      <geom class="visual" type="box" size="0.1 0.1 0.05"/>
      <geom class="collision" type="box" size="0.1 0.1 0.05"/>
      <body name="thigh" pos="0 0 -0.05">
        <joint type="hinge" axis="0 1 0"/>
        <inertial pos="{com}" mass="1" diaginertia="0.01 0.01 0.002"/>
        <geom class="visual" type="mesh" mesh="shell"/>
        <geom class="collision" type="capsule" fromto="0 0 0 0 0 -0.3" size="0.03"/>
        <body name="foot" pos="0 0 -0.3">
          <joint type="hinge" axis="0 1 0"/>
          <inertial pos="0 0 -0.02" mass="0.2" diaginertia="0.001 0.001 0.001"/>
          <geom class="collision" type="sphere" size="0.025" pos="0 0 -0.02"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def shell(low, high) -> str:
    corners = [
        [x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1]) for z in (low[2], high[2])
    ]
    return " ".join(f"{v:g}" for corner in corners for v in corner)


def model(com: str = "0 0 -0.15", low=(-0.04, -0.04, -0.3), high=(0.04, 0.04, 0.0)):
    return mujoco.MjModel.from_xml_string(HAND_TUNED.format(shell=shell(low, high), com=com))


def test_a_hand_tuned_model_passes():
    result = check_plausibility(model())
    assert result.bodies == 3 and result.findings == []


def test_a_centre_of_mass_away_from_agreeing_geometry_is_a_wrong_inertial_origin():
    result = check_plausibility(model(com="0 0 0.25"))
    (finding,) = result.findings
    assert finding.body == "thigh" and finding.cause == "wrong origin" and not finding.fails
    assert "inertial <origin>" in finding.detail
    assert result.failures == [] and len(result.warnings) == 1


def test_a_mesh_turned_a_quarter_is_an_up_axis():
    # The shell lies along -y instead of -z: Y-up data read as Z-up.
    result = check_plausibility(model(low=(-0.04, -0.3, -0.04), high=(0.04, 0.0, 0.04)))
    (finding,) = result.findings
    assert finding.body == "thigh" and finding.cause == "up axis" and not finding.fails
    assert "'shell'" in finding.detail and "quarter turn about x" in finding.detail


def mm_urdf() -> str:
    inertia = '<inertia ixx="0.01" iyy="0.01" izz="0.002" ixy="0" ixz="0" iyz="0"/>'
    return f"""<?xml version="1.0" encoding="utf-8"?>
<robot name="mm">
  <link name="base"><inertial><mass value="2"/>{inertia}</inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><inertial><origin xyz="0 0 -0.2"/><mass value="1"/>{inertia}</inertial>
    <visual><geometry><mesh filename="meshes/upper.stl"/></geometry></visual>
    <collision><geometry><mesh filename="meshes/upper.stl"/></geometry></collision></link>
  <link name="lower"><inertial><origin xyz="0 0 -0.2"/><mass value="1"/>{inertia}</inertial>
    <visual><geometry><mesh filename="meshes/upper.stl"/></geometry></visual>
    <collision><origin xyz="0 0 -0.2"/><geometry><box size="0.06 0.1 0.4"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 -0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="50" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 -0.4"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="50" velocity="1"/></joint>
</robot>
"""


def test_a_mesh_in_millimetres_fails_the_check_with_its_likely_cause(tmp_path):
    # 400 mm long, exported in millimetres: 400 "metres" to MuJoCo.
    box = trimesh.creation.box([60.0, 100.0, 400.0])
    box.apply_translation([0, 0, -200.0])
    (tmp_path / "meshes").mkdir()
    box.export(tmp_path / "meshes" / "upper.stl")
    write(tmp_path / "robot.urdf", mm_urdf())
    simple_manifest(tmp_path)
    done = run_cli("build", cwd=tmp_path)
    assert done.code == EXIT_CHECK, done.stderr
    assert "units in mm" in done.stderr and "Traceback" not in done.stderr
    check = json.loads((tmp_path / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    findings = {f["body"]: f for f in check["plausibility"]["findings"]}
    # 'upper' has only the mesh (visual and collision): compared with the robot's joints;
    # 'lower' has an authored box beside it.
    assert set(findings) == {"upper", "lower"}
    assert all(f["cause"] == "units in mm" and f["fails"] for f in findings.values())
    assert "the robot's joint layout" in findings["upper"]["detail"]
    assert "its body's other geometry" in findings["lower"]["detail"]
    assert any("body 'lower'" in failure for failure in check["failures"])
    page = (tmp_path / "mjcf" / "report" / "report.md").read_text()
    assert "## Mesh plausibility" in page and "| lower | fails |" in page
    # Scaled to metres in the URDF, the same mesh passes.
    urdf = (tmp_path / "robot.urdf").read_text()
    write(
        tmp_path / "robot.urdf",
        urdf.replace('upper.stl"/>', 'upper.stl" scale="0.001 0.001 0.001"/>'),
    )
    done = run_cli("build", cwd=tmp_path)
    assert done.code == 0, done.stderr
    check = json.loads((tmp_path / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    assert check["plausibility"]["findings"] == []
    assert np.isfinite(check["plausibility"]["bodies"])
