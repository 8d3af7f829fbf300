"""Masses from geometry (robot.yaml's ``inertia.missing: geometry``) against MuJoCo's own URDF
import, which gives a link without ``<inertial>`` the mass of its collision geometry at 1000
kg/m^3; and the default, which invents no mass, unchanged."""

from __future__ import annotations

import json
import os
from pathlib import Path

import mujoco
import numpy as np
import pytest

from mjcfbuild.errors import EXIT_INPUT
from mjcfbuild.mjcf.inertia import InertiaPolicy
from tests.conftest import run_cli, simple_manifest, write

LIMIT = '<limit lower="-2" upper="2" effort="50" velocity="2"/>'

# A kinematics-only arm of primitives (a vendor arm made for visualisation): no <inertial>
# anywhere; a camera fixed to the forearm (fused into its body, as MuJoCo fuses it); a chain of
# ghost links without geometry (urdf-usd-converter's link_skip_ghost_link_chain.urdf).
ARM = f"""<?xml version="1.0"?>
<robot name="ghost_arm">
  <link name="base">
    <visual><geometry><cylinder radius="0.1" length="0.1"/></geometry></visual>
    <collision><geometry><cylinder radius="0.1" length="0.1"/></geometry></collision>
  </link>
  <link name="ghost_1"/>
  <link name="ghost_2"/>
  <link name="shoulder">
    <collision><origin xyz="0 0 0.05" rpy="0.3 0.2 0.1"/><geometry><box size="0.08 0.06 0.1"/></geometry></collision>
  </link>
  <link name="upper_arm">
    <visual><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.04" length="0.3"/></geometry></visual>
    <collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.04" length="0.3"/></geometry></collision>
    <collision><origin xyz="0 0 0.3"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <link name="forearm">
    FOREARM
  </link>
  <link name="camera">
    <collision><geometry><box size="0.03 0.05 0.02"/></geometry></collision>
  </link>
  <link name="tool">
    <collision><geometry><sphere radius="0.02"/></geometry></collision>
  </link>
  <joint name="g1" type="fixed"><parent link="base"/><child link="ghost_1"/><origin xyz="0 0 0.05"/></joint>
  <joint name="g2" type="fixed"><parent link="ghost_1"/><child link="ghost_2"/></joint>
  <joint name="j1" type="revolute"><parent link="ghost_2"/><child link="shoulder"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="j2" type="revolute"><parent link="shoulder"/><child link="upper_arm"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>{LIMIT}</joint>
  <joint name="j3" type="revolute"><parent link="upper_arm"/><child link="forearm"/><origin xyz="0 0 0.3"/><axis xyz="0 1 0"/>{LIMIT}</joint>
  <joint name="cam" type="fixed"><parent link="forearm"/><child link="camera"/><origin xyz="0.05 0 0.1" rpy="0 0 0.5"/></joint>
  <joint name="j4" type="revolute"><parent link="forearm"/><child link="tool"/><origin xyz="0 0 0.3"/><axis xyz="1 0 0"/>{LIMIT}</joint>
</robot>
"""
PRIMITIVE_FOREARM = (
    '<collision><origin xyz="0 0 0.15" rpy="0 0.1 0"/>'
    '<geometry><capsule radius="0.035" length="0.2"/></geometry></collision>'
)
# Turned and stretched: the mesh is weighed as the model holds it.
MESH_FOREARM = (
    '<visual><geometry><mesh filename="forearm.stl"/></geometry></visual>'
    '<collision><origin xyz="0 0 0.01" rpy="0 0.1 0"/>'
    '<geometry><mesh filename="forearm.stl" scale="1 1 1.5"/></geometry></collision>'
)


def _forearm_mesh(folder: Path) -> None:
    import trimesh

    mesh = trimesh.creation.capsule(height=0.2, radius=0.04, count=[16, 16])
    mesh.apply_translation([0.01, 0.02, 0.05])
    mesh.export(folder / "forearm.stl")


def _tensor(model, body: int) -> np.ndarray:
    flat = np.zeros(9)
    mujoco.mju_quat2Mat(flat, model.body_iquat[body])
    rotation = flat.reshape(3, 3)
    return rotation @ np.diag(model.body_inertia[body]) @ rotation.T


def _mujocos_own(urdf: Path):
    """MuJoCo's own import of ``urdf`` (meshes relative to its folder)."""
    here = Path.cwd()
    os.chdir(urdf.parent)
    try:
        return mujoco.MjModel.from_xml_path(str(urdf))
    finally:
        os.chdir(here)


def _assert_masses_as_mujocos_import(urdf: Path, built: Path) -> int:
    """Every moving body of MuJoCo's own import of ``urdf`` has, in the built model, the same
    mass, centre of mass and inertia (1e-9 relative); the number of bodies compared."""
    reference = _mujocos_own(urdf)
    model = mujoco.MjModel.from_xml_path(str(built))
    compared = 0
    for body in range(1, reference.nbody):
        name = mujoco.mj_id2name(reference, mujoco.mjtObj.mjOBJ_BODY, body)
        ours = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
        assert ours > 0, name
        mass = reference.body_mass[body]
        assert mass > 0
        assert abs(model.body_mass[ours] - mass) <= 1e-9 * mass, name
        assert np.allclose(model.body_ipos[ours], reference.body_ipos[body], rtol=0, atol=1e-9)
        tensor = _tensor(reference, body)
        scale = np.max(np.abs(tensor))
        assert np.max(np.abs(_tensor(model, ours) - tensor)) <= 1e-9 * scale, name
        compared += 1
    return compared


@pytest.mark.parametrize("forearm", ["primitive", "mesh", "mesh collided as its hull"])
def test_a_kinematics_only_arm_gets_the_masses_mujocos_import_gives_it(tmp_path, forearm):
    """Built with ``missing: geometry``, a description without any <inertial> builds, its
    check passes, and every moving body has the mass, centre of mass and inertia MuJoCo's own
    URDF import gives it; each link weighed is one warning at its line, and the check's
    masses line says the mass comes from geometry, not from the URDF."""
    if forearm != "primitive":
        _forearm_mesh(tmp_path)
    text = ARM.replace("FOREARM", PRIMITIVE_FOREARM if forearm == "primitive" else MESH_FOREARM)
    urdf = write(tmp_path / "robot.urdf", text)
    # A hull changes what the link collides with, not what it weighs: the mesh's own volume.
    hull = "collision: {default: hull}\n" if "hull" in forearm else ""
    manifest = simple_manifest(tmp_path, extra=f"check: {{previews: false, tuning: false}}\n{hull}")
    plain = manifest.read_text()

    # The default is unchanged: a description with no mass is refused, naming the option.
    done = run_cli("build", "-j", "1", cwd=tmp_path)
    assert done.code == EXIT_INPUT, done.stderr
    assert (
        "no link of the robot has a mass (<inertial>), so its 4 moving bodies cannot be "
        "simulated (add each link's <inertial> (mass, centre of mass, inertia) to the "
        "description: MuJoCo needs them to simulate it, or set inertia: {missing: geometry} in "
        "robot.yaml to give each link the mass of its geometry, as MuJoCo's own URDF import "
        "does)"
    ) in done.stderr

    manifest.write_text(plain + "inertia: {missing: geometry}\n")
    done = run_cli("build", "-j", "1", cwd=tmp_path)
    assert done.code == 0, done.stderr
    assert _assert_masses_as_mujocos_import(urdf, tmp_path / "mjcf" / "robot.xml") == 4
    report = (tmp_path / "mjcf" / "report" / "report.md").read_text()
    built = json.loads((tmp_path / "mjcf" / "report" / "report.json").read_text())
    line = next(n for n, row in enumerate(text.splitlines(), 1) if 'link name="shoulder"' in row)
    warning = (
        f"robot.urdf:{line}: link 'shoulder' has no <inertial>: given 0.48 kg from its "
        "collision geometry at 1000 kg/m^3 (inertia.missing: geometry)"
    )
    assert warning in built["warnings"]
    # The console groups them: the first whole, the others by name.
    assert (
        "robot.urdf:3: link 'base' has no <inertial>: given 3.142 kg from its collision "
        "geometry at 1000 kg/m^3 (inertia.missing: geometry) (and 5 more like it: shoulder, "
        "upper_arm, forearm, "
    ) in done.stderr
    weighed = [w.split("'")[1] for w in built["warnings"] if "(inertia.missing: geometry)" in w]
    # One line per link, none for the ghosts (no geometry, nothing to weigh).
    assert weighed == ["base", "shoulder", "upper_arm", "forearm", "camera", "tool"]
    check = built["check"]
    assert check["passes"], check["failures"]
    masses = check["masses"]
    assert masses["urdf_total"] == 0 and masses["problems"] == []
    assert masses["placeholder_bodies"] == []
    assert masses["from_geometry"] == ["base", "shoulder", "upper_arm", "forearm", "camera", "tool"]
    assert abs(masses["model_total"] - masses["geometry_total"]) < 1e-9
    done = run_cli("check", cwd=tmp_path)
    assert done.code == 0, done.stderr
    row = next(row for row in done.stdout.splitlines() if row.strip().startswith("masses"))
    assert (
        f"{masses['model_total']:.6g} kg (URDF 0 kg; {masses['geometry_total']:.6g} kg of it "
        "from the geometry of 6 links without a mass in the URDF, at 1000 kg/m^3: "
        "inertia.missing: geometry), 0 problems"
    ) in row
    assert "## Masses from geometry" in report and "| shoulder | collision geometry | 0.48 |" in (
        report
    )


def test_a_ghost_root_floating_a_box_weighs_as_mujocos_import(tmp_path):
    """urdf-usd-converter's link_first_ghost_link_floating.urdf: an empty root holds a box by
    a floating joint, a second box fixed to it; MuJoCo's import floats 1125 kg."""
    urdf = write(
        tmp_path / "robot.urdf",
        """<robot name="ghost_float"><link name="BaseLink"/>
  <link name="link1"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="link_box"><collision><geometry><box size="0.5 0.5 0.5"/></geometry></collision></link>
  <joint name="joint1" type="floating"><origin xyz="0 0 1"/><parent link="BaseLink"/><child link="link1"/></joint>
  <joint name="joint_box" type="fixed"><origin xyz="0 0 0.8"/><parent link="link1"/><child link="link_box"/></joint>
</robot>
""",
    )
    simple_manifest(
        tmp_path, extra="check: {previews: false, tuning: false}\ninertia: {missing: geometry}\n"
    )
    done = run_cli("build", "-j", "1", cwd=tmp_path)
    assert done.code == 0, done.stderr
    assert _assert_masses_as_mujocos_import(urdf, tmp_path / "mjcf" / "robot.xml") == 1
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "robot.xml"))
    assert abs(float(np.sum(model.body_mass)) - 1125.0) < 1e-9


def test_density_scales_the_masses_and_a_visual_only_link_is_named_so(tmp_path):
    """``density`` is the geometry's; a link with only visual geometry is weighed from it
    (MuJoCo's import discards visuals) and its warning says which geometry."""
    from tests.mjcf.helpers import build

    urdf = """<robot name="r"><link name="base"/>
      <link name="arm"><collision><geometry><box size="0.1 0.1 0.5"/></geometry></collision></link>
      <link name="tip"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
      <joint name="k" type="revolute"><parent link="arm"/><child link="tip"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
    </robot>"""
    policy = InertiaPolicy(missing="geometry", density=2700.0)
    assembly, model = build(urdf, tmp_path, inertia=policy)
    assert [round(record.mass, 9) for record in assembly.geometry_masses] == [13.5, 2.7]
    arm, tip = (mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name) for name in ("arm", "tip"))
    assert abs(model.body_mass[arm] - 13.5) < 1e-9 and abs(model.body_mass[tip] - 2.7) < 1e-9
    assert (
        "robot.urdf:2: link 'arm' has no <inertial>: given 13.5 kg from its collision geometry "
        "at 2700 kg/m^3 (inertia.missing: geometry)"
    ) in assembly.warnings
    assert (
        "robot.urdf:3: link 'tip' has no <inertial>: given 2.7 kg from its visual geometry (it "
        "has no <collision>) at 2700 kg/m^3 (inertia.missing: geometry)"
    ) in assembly.warnings
    assert assembly.repairs == []


def test_by_default_a_link_without_mass_keeps_the_placeholder(tmp_path):
    """mjcfbuild invents no mass unasked: a moving link with no <inertial> gets the
    placeholder (inertia.min_mass), reported as a repair, and nothing is weighed."""
    from tests.mjcf.helpers import build

    inertial = (
        '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" '
        'ixz="0" iyz="0"/></inertial>'
    )
    urdf = f"""<robot name="r"><link name="base">{inertial}</link>
      <link name="arm"><collision><geometry><box size="0.1 0.1 0.5"/></geometry></collision></link>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
    </robot>"""
    assembly, model = build(urdf, tmp_path)
    arm = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "arm")
    assert assembly.geometry_masses == []
    assert abs(model.body_mass[arm] - InertiaPolicy().min_mass) < 1e-12
    assert "moving body with too small a mass" in [repair.problem for repair in assembly.repairs]
    assert not any("inertia.missing" in warning for warning in assembly.warnings)
    # Asked for, the same link weighs 5 kg, and nothing is repaired.
    assembly, model = build(urdf, tmp_path / "geometry", inertia=InertiaPolicy(missing="geometry"))
    assert abs(model.body_mass[arm] - 5.0) < 1e-9 and assembly.repairs == []


def test_geometry_that_encloses_no_volume_keeps_the_placeholder_with_a_warning(tmp_path):
    """An open mesh weighs nothing: the link keeps the placeholder, and the build says why."""
    import trimesh

    from tests.mjcf.helpers import build

    sheet = trimesh.Trimesh(
        vertices=[[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0.1, 0.1, 0]],
        faces=[[0, 1, 2], [1, 3, 2]],
    )
    sheet.export(tmp_path / "sheet.stl")
    urdf = """<robot name="r"><link name="base"/>
      <link name="flap"><visual><geometry><mesh filename="sheet.stl"/></geometry></visual></link>
      <link name="arm"><collision><geometry><box size="0.1 0.1 0.5"/></geometry></collision></link>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
      <joint name="k" type="revolute"><parent link="arm"/><child link="flap"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
    </robot>"""
    assembly, _ = build(urdf, tmp_path, inertia=InertiaPolicy(missing="geometry"))
    assert [record.link for record in assembly.geometry_masses] == ["arm"]
    assert (
        "robot.urdf:2: link 'flap' has no <inertial>, and its visual geometry encloses no "
        "volume, so inertia.missing: geometry cannot give it a mass: it keeps the placeholder "
        "mass (inertia.min_mass); give it an <inertial>"
    ) in assembly.warnings
    assert {repair.body for repair in assembly.repairs} == {"flap"}
