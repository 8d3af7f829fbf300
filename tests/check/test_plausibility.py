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
from tests.meshes.test_upaxis import box_triangles, dae_text

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


def forearm_urdf() -> str:
    """A forearm drawn by ``forearm.dae`` and colliding with a box, both reaching 20 cm along
    -y, whose centre of mass is written on the wrong side (+y): gym-jiminy-zoo's atlas."""
    inertia = '<inertia ixx="0.01" iyy="0.005" izz="0.01" ixy="0" ixz="0" iyz="0"/>'
    return f"""<?xml version="1.0"?>
<robot name="forearm">
  <link name="base"><inertial><mass value="5"/>{inertia}</inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="forearm">
    <inertial><origin xyz="0 0.083 0"/><mass value="2.5"/>{inertia}</inertial>
    <visual><geometry><mesh filename="forearm.dae"/></geometry></visual>
    <collision><origin xyz="0 -0.1 0"/><geometry><box size="0.1 0.2 0.06"/></geometry>
    </collision></link>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="forearm"/>
    <origin xyz="0 0 0.3"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="50" velocity="2"/></joint>
</robot>
"""


def build_forearm(tmp_path, extra: str = "") -> dict:
    """Build the forearm, its DAE tagged Y-up holding Z-up data (read as pycollada reads it,
    it lies along its collision box); the plausibility findings by body."""
    corners, faces = box_triangles(np.array([-0.05, -0.2, -0.03]), np.array([0.05, 0.0, 0.03]))
    write(tmp_path / "forearm.dae", dae_text(corners, faces, "Y_UP"))
    write(tmp_path / "robot.urdf", forearm_urdf())
    simple_manifest(tmp_path, extra=extra)
    done = run_cli("build", cwd=tmp_path)
    assert done.code == 0, done.stderr
    check = json.loads((tmp_path / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    return {f["body"]: f for f in check["plausibility"]["findings"]}


def test_a_mesh_that_agrees_with_its_collision_box_blames_the_inertial_not_the_up_axis(tmp_path):
    """The centre of mass fits the mesh turned a quarter, but the mesh as read already lies
    along its link's collision box: the turn is no evidence, the inertial <origin> is."""
    findings = build_forearm(tmp_path)
    assert set(findings) == {"forearm"}
    assert findings["forearm"]["cause"] == "wrong origin", findings
    assert "a wrong inertial <origin>" in findings["forearm"]["detail"]


def test_a_dae_turned_away_from_its_collision_box_by_robot_yaml_is_named(tmp_path):
    """Following the up-axis advice turned the mesh across its collision box, and the centre
    of mass then fit the larger box of both: the check passed silently."""
    findings = build_forearm(tmp_path, "meshes:\n  collada_up_axis_files: {forearm.dae: apply}\n")
    (problem,) = findings["forearm"]["problems"]
    assert findings["forearm"]["cause"] == "up axis" and not findings["forearm"]["fails"]
    assert problem.startswith("mesh 'forearm', turned to Z-up as its DAE file's Y_UP tag says")
    assert "collada_up_axis_files for its DAE file to ignore" in findings["forearm"]["detail"]


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


def arm_urdf(mass: float, inertia: float, base: str = "") -> str:
    """A base and a 30 cm arm link of ``mass`` (a 5 x 5 x 30 cm box: 1.5 kg of aluminium)."""
    arm_inertia = (
        f'<inertia ixx="{inertia}" iyy="{inertia}" izz="{inertia / 10}" ixy="0" ixz="0" iyz="0"/>'
    )
    return f"""<?xml version="1.0" encoding="utf-8"?>
<robot name="arm">
{base}  <link name="base"><inertial><mass value="2"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="arm">
    <inertial><origin xyz="0 0 -0.15"/><mass value="{mass}"/>{arm_inertia}</inertial>
    <visual><origin xyz="0 0 -0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry></visual>
    <collision><origin xyz="0 0 -0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry>
    </collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 -0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="50" velocity="1"/></joint>
</robot>
"""


ARM_LINK, BASE_LINK = '<link name="arm">', '<link name="base">'


def line_of(text: str, fragment: str) -> int:
    return next(n for n, line in enumerate(text.splitlines(), 1) if fragment in line)


def build_arm(tmp_path, urdf: str):
    write(tmp_path / "robot.urdf", urdf)
    simple_manifest(tmp_path)
    done = run_cli("build", cwd=tmp_path)
    check = json.loads((tmp_path / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    return done, check


def test_a_link_in_kilograms_passes(tmp_path):
    done, check = build_arm(tmp_path, arm_urdf(1.5, 0.0115))
    assert done.code == 0, done.stderr
    assert check["plausibility"]["findings"] == []


def test_a_link_in_grams_fails_the_check_at_its_urdf_line(tmp_path):
    urdf = arm_urdf(1500.0, 11.5)  # 1.5 kg written in grams (and g m^2)
    done, check = build_arm(tmp_path, urdf)
    assert done.code == EXIT_CHECK and "Traceback" not in done.stderr
    (finding,) = check["plausibility"]["findings"]
    assert finding["body"] == "arm" and finding["cause"] == "mass units" and finding["fails"]
    where = f"robot.urdf:{line_of(urdf, ARM_LINK)}"
    assert finding["where"] == where
    assert "grams written as kilograms" in finding["detail"]
    (line,) = [line for line in done.stderr.splitlines() if "kg/m^3" in line]
    assert f"{where}: check: body 'arm'" in line
    assert "2e+06 kg/m^3" in line and "grams" in line
    page = (tmp_path / "mjcf" / "report" / "report.md").read_text()
    assert f"| arm ({where}) | fails |" in page


def test_a_link_in_tonnes_fails_the_check(tmp_path):
    done, check = build_arm(tmp_path, arm_urdf(0.0015, 1.15e-5))  # 1.5 kg written in tonnes
    assert done.code == EXIT_CHECK, done.stderr
    (finding,) = check["plausibility"]["findings"]
    assert finding["body"] == "arm" and finding["fails"]
    assert "lighter than anything robots are made of" in finding["problems"][0]
    assert "tonnes written as kilograms" in finding["detail"]


def marked_arm_urdf(arm_mass: float, marker_length: float) -> str:
    """The arm with a massless link fused onto it whose only geometry is a thin see-through
    cylinder ``marker_length`` long (a gunsight, a sensor's field of view), as PyFlyt's
    acrowing has."""
    marker = (
        '  <link name="sight"><inertial><mass value="0"/>\n'
        '    <inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial>\n'
        f'    <visual><geometry><cylinder radius="0.15" length="{marker_length}"/></geometry>'
        "</visual></link>\n"
        '  <joint name="sight_joint" type="fixed"><parent link="arm"/><child link="sight"/>\n'
        '    <origin xyz="10 0 0" rpy="0 1.5708 0"/></joint>\n'
    )
    return arm_urdf(arm_mass, arm_mass / 1.5 * 0.0115).replace("</robot>", marker + "</robot>")


def test_a_massless_marker_fused_into_a_link_is_warned_about_not_failed(tmp_path):
    """A 20 m see-through cylinder on a massless link makes the arm look 1 kg/m^3: the check
    failed the build, blaming a mass in tonnes. It now warns, naming the marker link; the
    same arm really written in tonnes, with a marker too small to decide, still fails."""
    urdf = marked_arm_urdf(1.5, 20.0)
    done, check = build_arm(tmp_path / "marker", urdf)
    assert done.code == 0, done.stderr
    (finding,) = check["plausibility"]["findings"]
    assert finding["body"] == "arm" and not finding["fails"]
    sight = line_of(urdf, '<link name="sight">')
    assert f"link 'sight' (line {sight})" in finding["detail"]
    assert "tonnes" not in finding["detail"]
    done, check = build_arm(tmp_path / "tonnes", marked_arm_urdf(0.0015, 0.01))
    assert done.code == EXIT_CHECK, done.stderr
    (finding,) = check["plausibility"]["findings"]
    assert finding["fails"] and "tonnes written as kilograms" in finding["detail"]


def test_a_link_welded_to_the_world_is_judged_and_its_impossible_inertia_reported(tmp_path):
    world = (
        '  <link name="world"/>\n'
        '  <joint name="weld" type="fixed"><parent link="world"/><child link="base"/></joint>\n'
    )
    urdf = arm_urdf(1.5, 0.0115, world).replace('<mass value="2"/>', '<mass value="2000"/>')
    urdf = urdf.replace('izz="0.01" ixy="0"', 'izz="0.05" ixy="0"', 1)  # 0.01 + 0.01 < 0.05
    done, check = build_arm(tmp_path, urdf)
    # The world's mass is MuJoCo's to drop: the model simulates the same, so warnings only.
    assert done.code == 0, done.stderr
    findings = {f["cause"]: f for f in check["plausibility"]["findings"]}
    assert set(findings) == {"mass units", "impossible inertia"}
    dense = findings["mass units"]
    assert dense["body"] == "world" and not dense["fails"]
    assert "links welded to the world: base" in dense["problems"][0]
    assert dense["where"] == f"robot.urdf:{line_of(urdf, BASE_LINK)}"
    inertia = findings["impossible inertia"]
    assert inertia["subject"] == "link" and inertia["body"] == "base" and not inertia["fails"]
    assert "break A + B >= C" in inertia["problems"][0]
    assert len(check["plausibility"]["warnings"]) == 2
    assert "link 'base'" in done.stdout + done.stderr


def fingers(mass: float, inertia: float, extra: str = "") -> mujoco.MjModel:
    """A palm and three 2 x 2 x 5 cm fingers of ``mass`` each (20 g of plastic: 1,000 kg/m^3)."""
    finger = (
        '<body name="{name}" pos="{x} 0 0.05"><joint type="hinge" axis="0 1 0"/>'
        f'<inertial pos="0 0 0.025" mass="{mass}" diaginertia="{inertia} {inertia} '
        f'{inertia / 4}"/>'
        '<geom type="box" size="0.01 0.01 0.025" pos="0 0 0.025"/></body>'
    )
    bodies = "".join(finger.format(name=f"finger{i}", x=0.03 * i) for i in range(3))
    return mujoco.MjModel.from_xml_string(
        f"""<mujoco><worldbody><body name="palm"><freejoint/>
        <inertial pos="0 0 0" mass="0.3" diaginertia="3e-4 3e-4 3e-4"/>
        <geom type="box" size="0.05 0.05 0.02"/>{bodies}{extra}</body></worldbody></mujoco>"""
    )


def test_a_hand_in_kilograms_passes():
    assert check_plausibility(fingers(0.02, 5e-6)).findings == []


def test_fingers_too_light_to_judge_alone_are_judged_as_the_whole_robot():
    # Each finger in tonnes (2e-5) is below the lightest body judged alone, the palm too.
    model = fingers(2e-5, 5e-9)
    model.body_mass[1] = 3e-4  # the palm in tonnes as well
    found = check_plausibility(model)
    (finding,) = found.findings
    assert finding.subject == "robot" and finding.fails and finding.cause == "mass units"
    assert "in all:" in finding.problems[0] and "tonnes" in finding.detail


def test_mass_on_a_body_without_geometry_counts_in_the_robots_total():
    extra = (
        '<body name="counterweight"><joint type="hinge"/>'
        '<inertial pos="0 0 0" mass="50000" diaginertia="1 1 1"/></body>'
    )
    found = check_plausibility(fingers(0.02, 5e-6, extra))
    (finding,) = found.findings
    assert finding.subject == "robot" and finding.fails
    assert "denser than anything robots are made of" in finding.problems[0]


def test_geometry_that_only_marks_a_link_says_nothing_of_its_mass():
    # TIAGo's hand links: 50 g on a 1 mm sphere, with an inertia that puts the mass 14 cm
    # out ("to stabilize simulation"). The sphere is a marker, not the part.
    model = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody><body name="hand"><joint type="hinge"/>
        <inertial pos="0 0 0" mass="0.05" diaginertia="0.001 0.001 0.001"/>
        <geom type="sphere" size="0.001"/></body></worldbody></mujoco>"""
    )
    assert check_plausibility(model).findings == []


def test_a_link_in_grams_written_in_xacro_is_named_at_its_xacro_line(tmp_path):
    urdf = arm_urdf(1500.0, 11.5).replace(
        '<robot name="arm">', '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'
    )
    write(tmp_path / "robot.urdf.xacro", urdf)
    simple_manifest(tmp_path, "xacro: robot.urdf.xacro")
    done = run_cli("build", cwd=tmp_path)
    assert done.code == EXIT_CHECK
    (line,) = [line for line in done.stderr.splitlines() if "kg/m^3" in line]
    assert f"robot.urdf.xacro:{line_of(urdf, ARM_LINK)}: check: body 'arm'" in line, line


def test_a_fake_link_drawn_as_a_point_says_nothing_of_its_mass():
    # gym-ignition's character: 10 g "fake" links between hinges, invisible 0.5 mm spheres.
    model = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody><body name="fake"><joint type="hinge"/>
        <inertial pos="0 0 0" mass="0.01" diaginertia="1e-9 1e-9 1e-9"/>
        <geom type="sphere" size="0.0005" contype="0" conaffinity="0"/></body>
        </worldbody></mujoco>"""
    )
    assert check_plausibility(model).findings == []


def test_a_heavy_body_welded_to_the_world_is_a_warning():
    # gym-ignition's pendulum: a 1 t support (a 5 x 10 x 60 cm box) that never moves.
    model = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody><body name="support">
        <inertial pos="0 0 0.3" mass="1000" diaginertia="30 30 1"/>
        <geom type="box" size="0.025 0.05 0.3" pos="0 0 0.3"/>
        <body name="arm" pos="0 0 0.6"><joint type="hinge" axis="0 1 0"/>
          <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" density="2000"/></body>
        </body></worldbody></mujoco>"""
    )
    found = check_plausibility(model)
    (finding,) = found.findings
    assert finding.body == "support" and not finding.fails and finding.cause == "mass units"
    assert "welded to the world" in finding.problems[0] and found.failures == []


def test_a_moving_link_without_a_mass_is_said_in_the_verdict(tmp_path):
    """A kinematics-grade arm (hpp's Staubli: 5 of 6 links without <inertial>) passed every
    check as a 1.5 g robot, its 0.1 g placeholders said only among the build's warnings."""
    import re

    urdf = arm_urdf(1.5, 0.0115)
    arm = urdf.index(ARM_LINK)
    urdf = urdf[:arm] + re.sub(r"<inertial>.*?</inertial>", "", urdf[arm:], count=1, flags=re.S)
    write(tmp_path / "robot.urdf", urdf)
    simple_manifest(tmp_path)
    built = run_cli("build", cwd=tmp_path)
    assert built.code == 0, built.stderr
    checked = run_cli("check", cwd=tmp_path)
    assert "1 moving body without a mass in the URDF" in checked.stdout
    assert (
        "checks pass, but 1 moving body ('arm') has no mass in the URDF (no <inertial>): the "
        "model moves it with a placeholder mass, so its dynamics are not the robot's"
    ) in checked.stdout
    check = json.loads((tmp_path / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    assert check["masses"]["placeholder_bodies"] == ["arm"]


def test_a_massless_link_drawn_with_a_mesh_is_named_as_the_cause_and_still_fails(tmp_path):
    """A wrist whose mesh link has no <inertial> and whose tool gives it 1.5 g: failed as "a
    mass in tonnes", when the link without a mass is as likely; named now, still failing (a
    mesh's volume the URDF does not tell, so it cannot excuse the body)."""
    import shutil

    from tests.conftest import EXAMPLES

    cover = (
        '  <link name="cover"><visual><geometry><mesh filename="cover.stl"/></geometry>'
        "</visual></link>\n"
        '  <joint name="cover_joint" type="fixed"><parent link="arm"/><child link="cover"/>'
        "</joint>\n"
    )
    urdf = arm_urdf(0.0015, 1.15e-5).replace("</robot>", cover + "</robot>")
    shutil.copy(EXAMPLES / "arm" / "meshes" / "base.stl", tmp_path / "cover.stl")
    done, check = build_arm(tmp_path, urdf)
    assert done.code == EXIT_CHECK, done.stderr
    (finding,) = check["plausibility"]["findings"]
    assert finding["fails"]
    assert "link 'cover' (line" in finding["detail"] and "no mass in the URDF" in finding["detail"]
