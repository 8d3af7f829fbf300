"""The assembled model: classes, sites, meshes, free joint, compile errors with URDF lines."""

from __future__ import annotations

import pytest
from lxml import etree

from mjcfbuild.errors import ModelError
from tests.conftest import EXAMPLES, INERTIA, two_link_urdf
from tests.mjcf.helpers import build


def test_geoms_live_in_visual_and_collision_classes(tmp_path):
    assembly, model = build(two_link_urdf(), tmp_path)
    root = etree.fromstring(assembly.xml)
    classes = [g.get("class") for g in root.find("worldbody").iter("geom")]
    assert sorted(set(classes)) == ["collision", "visual"]
    visual = root.find(".//default[@class='visual']/geom")
    assert (visual.get("group"), visual.get("contype"), visual.get("conaffinity")) == (
        "2",
        "0",
        "0",
    )
    assert root.find(".//default[@class='collision']/geom").get("group") == "3"
    # authored collision geometry is kept: the cylinder, not the visual
    assert model.ngeom == 3


def test_every_link_is_a_body_or_a_site(tmp_path):
    urdf = two_link_urdf(
        extra='<link name="tool"/><joint name="t" type="fixed"><parent link="arm"/><child link="tool"/>'
        '<origin xyz="0 0 0.5"/></joint>'
    )
    _, model = build(urdf, tmp_path, link_sites="fused")
    import mujoco

    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "arm") >= 0
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "tool") >= 0
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "arm") == -1
    _, model = build(urdf, tmp_path, link_sites="all")
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "arm") >= 0


def test_free_joint_on_the_root(tmp_path):
    _, model = build(two_link_urdf(), tmp_path, free_joint=True)
    assert model.jnt_type[0] == 0  # mjJNT_FREE
    assert model.nq == 7 + 1


def test_free_joint_when_the_root_is_world(tmp_path):
    urdf = two_link_urdf(
        extra='<link name="world"/><joint name="w" type="fixed"><parent link="world"/>'
        '<child link="base"/></joint>'
    )
    _, model = build(urdf, tmp_path, free_joint=True)
    assert model.nq == 8


def test_free_joint_when_the_world_holds_two_links_floats_them_together(tmp_path):
    # A camera mount bolted to `world` beside the base: one free joint, on the base (the
    # heavier), and the mount rides with it instead of floating off (and falling) alone.
    import mujoco

    urdf = two_link_urdf(
        extra='<link name="world"/><joint name="w" type="fixed"><parent link="world"/>'
        f'<child link="base"/></joint><link name="mount">{INERTIA}</link>'
        '<joint name="wm" type="fixed"><parent link="world"/><child link="mount"/>'
        '<origin xyz="1 0 1"/></joint>'
    )
    _, model = build(urdf, tmp_path, free_joint=True, fuse_static=False)
    assert list(model.jnt_type).count(mujoco.mjtJoint.mjJNT_FREE) == 1
    assert model.nq == 8
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data, 50)
    base, mount = (mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, n) for n in ("base", "mount"))
    assert data.xpos[mount] - data.xpos[base] == pytest.approx([1, 0, 1])


def test_free_joint_says_when_the_world_holds_the_robot_only_by_a_moving_joint(tmp_path):
    urdf = two_link_urdf(
        extra='<link name="world"/><joint name="turntable" type="continuous">'
        '<parent link="world"/><child link="base"/><axis xyz="0 0 1"/></joint>'
    )
    assembly, model = build(urdf, tmp_path, free_joint=True)
    assert model.nq == 2
    (warning,) = [w for w in assembly.warnings if "free_joint" in w]
    assert "floats nothing" in warning and "'turntable'" in warning, warning


@pytest.mark.parametrize("free_joint", [False, True])
def test_a_floating_joint_from_a_placeholder_root_floats_the_robot(tmp_path, free_joint):
    # HyQReal2's layout: a massless root link holds the trunk by a floating joint. MuJoCo's
    # own import takes the root for the world; the build stopped at "free joint can only be
    # used on top level", advising the free_joint it already had.
    import mujoco

    urdf = two_link_urdf(
        extra='<link name="root"/><joint name="float" type="floating"><parent link="root"/>'
        '<child link="base"/><origin xyz="0 0 0.5"/></joint>'
    )
    _, model = build(urdf, tmp_path, free_joint=free_joint)
    assert list(model.jnt_type).count(mujoco.mjtJoint.mjJNT_FREE) == 1
    assert model.joint(0).name == "float" and model.body(model.jnt_bodyid[0]).name == "base"
    assert model.site_bodyid[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "root")] == 0


def test_a_floating_joint_below_links_fixed_to_the_root_floats_the_robot(tmp_path):
    # world -> fixed -> footprint -> floating -> base: fused, the floating joint hangs from the
    # world, as MuJoCo's own import reads it (the first refusal of nested floating joints
    # stopped it).
    import mujoco

    urdf = two_link_urdf(
        extra='<link name="world"/><link name="footprint"/><joint name="w" type="fixed">'
        '<parent link="world"/><child link="footprint"/></joint><joint name="float" '
        'type="floating"><parent link="footprint"/><child link="base"/></joint>'
    )
    _, model = build(urdf, tmp_path)
    assert model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE and model.joint(0).name == "float"


def test_a_root_with_mass_that_holds_a_floating_joint_says_what_stays_in_the_world(tmp_path):
    urdf = two_link_urdf(
        extra='<link name="ball">' + INERTIA + '</link><joint name="float" type="floating">'
        '<parent link="base"/><child link="ball"/><origin xyz="1 0 1"/></joint>'
    )
    assembly, _ = build(urdf, tmp_path)
    (note,) = [w for w in assembly.warnings if "stands for the world" in w]
    assert "link 'base' holds the robot by the floating joint 'float'" in note
    assert "its 1 kg, its geometry, joint hinge stay fixed there" in note


def test_a_world_link_with_an_inertia_mujoco_refuses_builds(tmp_path):
    # drake's Pendulum.urdf gives its root link 'world' the moments 0.01, 0, 0 (a stub for a
    # viewer): the world never moves, so its mass is left out instead of stopping the build
    urdf = two_link_urdf(
        extra='<link name="world"><inertial><mass value="0.01"/>'
        '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>'
        '<joint name="w" type="fixed"><parent link="world"/><child link="base"/></joint>'
    )
    assembly, model = build(urdf, tmp_path, fuse_static=False)
    assert model.nbody == 3  # the world, the base welded to it, the arm
    assert model.body_mass[0] == 0
    assert etree.fromstring(assembly.xml).find("worldbody/inertial") is None


def test_a_base_welded_to_an_undeclared_world_is_fixed(tmp_path):
    # drake's Acrobot.urdf: the parent 'world' is never declared; Drake welds to it
    urdf = two_link_urdf(
        extra='<joint name="w" type="fixed"><parent link="world"/><child link="base"/></joint>'
    )
    _, model = build(urdf, tmp_path)
    assert model.nbody == 2 and model.nq == 1  # the base is fused into the world


def test_mirrored_mesh_is_one_file_two_assets(tmp_path):
    meshes = EXAMPLES / "arm" / "meshes"
    urdf = f"""<robot name="r"><link name="a">{INERTIA}
      <visual><geometry><mesh filename="{meshes}/finger.stl"/></geometry></visual>
      <visual><geometry><mesh filename="{meshes}/finger.stl" scale="1 -1 1"/></geometry></visual>
    </link></robot>"""
    assembly, model = build(urdf, tmp_path)
    assert list(assembly.assets) == ["finger.obj"]
    assert model.nmesh == 2


def test_zero_size_visual_is_dropped_with_a_warning_collision_is_an_error(tmp_path):
    urdf = two_link_urdf().replace(
        '<visual><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.03"',
        '<visual><origin xyz="0 0 0.25"/><geometry><cylinder radius="0"',
    )
    assembly, _ = build(urdf, tmp_path)
    assert any("dropped" in w for w in assembly.warnings)
    with pytest.raises(Exception, match="collision 0 has box size 0 0 0"):
        build(two_link_urdf().replace('<box size="0.2 0.2 0.1"/>', '<box size="0 0 0"/>'), tmp_path)


def test_compile_errors_point_at_the_urdf_line(tmp_path):
    # A mesh with no volume makes MuJoCo's compiler fail; the error names the URDF line.
    flat = tmp_path / "flat.obj"
    flat.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
    urdf = f'<robot name="r"><link name="a">{INERTIA}\n<collision><geometry><mesh filename="{flat}"/></geometry></collision></link></robot>'
    with pytest.raises(ModelError) as info:
        build(urdf, tmp_path)
    assert info.value.location.file == "robot.urdf"
    assert info.value.location.line == 2


def test_mujoco_refusing_a_body_s_inertia_names_its_links_and_urdf_line(tmp_path):
    # Found by the long fuzz run: an inertial 2e12 m from its link, fused with a fixed child,
    # sums to principal moments MuJoCo refuses (A + B >= C broken in the last digits). The
    # error named no file, and told a URDF user to check mujoco_inputs they did not write.
    urdf = (
        '<robot name="fuzz">\n<link name="base"><inertial><origin xyz="0 0 2071817224192.0"/>'
        '<mass value="0.5"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/>'
        '</inertial></link>\n<link name="l1"/>\n<link name="l2"><inertial><mass value="0.5"/>'
        '<inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial></link>\n'
        '<joint name="j0" type="revolute"><parent link="base"/><child link="l1"/>'
        '<limit lower="0" upper="0" effort="1" velocity="1"/></joint>\n'
        '<joint name="j1" type="fixed"><parent link="base"/><child link="l2"/></joint>\n</robot>'
    )
    with pytest.raises(ModelError) as info:
        build(urdf, tmp_path, fuse_static=True)
    error = info.value
    assert (error.location.file, error.location.line) == ("robot.urdf", 2)
    assert "body 'base' (links base, l2 fused into it)" in error.one_line()
    assert "A + B >= C" in error.one_line() and "mujoco_inputs" not in error.one_line()


def test_free_joint_with_and_without_fusing(tmp_path):
    urdf = two_link_urdf(
        extra='<link name="tool"/><joint name="t" type="fixed"><parent link="arm"/><child link="tool"/>'
        '<origin xyz="0 0 0.5"/></joint>'
    )
    for fuse in (True, False):
        _, model = build(urdf, tmp_path / str(fuse), free_joint=True, fuse_static=fuse)
        assert model.jnt_type[0] == 0 and model.nq == 8
        assert model.nbody == (3 if fuse else 4)


def test_a_joint_with_lower_equal_upper_stays_locked(tmp_path):
    """MuJoCo ignores an empty range (the joint would turn freely); it gets a tiny one."""
    import mujoco

    urdf = two_link_urdf().replace('lower="-1.5" upper="1.5"', 'lower="0.2" upper="0.2"')
    assembly, model = build(urdf, tmp_path)
    hinge = model.joint("hinge")
    assert hinge.limited[0] == 1
    assert hinge.range == pytest.approx([0.2, 0.2], abs=2e-6)
    assert any("lower = upper = 0.2" in warning for warning in assembly.warnings)
    data = mujoco.MjData(model)
    data.qfrc_applied[0] = 5.0
    for _ in range(500):
        mujoco.mj_step(model, data)
    assert abs(data.qpos[0] - 0.2) < 0.05  # held like any joint at its limit (soft limits)


DRAWN = """<mujoco>
  <default>
    <default class="visual"><geom contype="0" conaffinity="0" group="2" density="0"/></default>
  </default>
  <asset>
    <mesh name="shell" file="shell.obj"/><mesh name="shared" file="shared.obj"/>
    <mesh name="badge" file="badge.obj"/>
  </asset>
  <worldbody>
    <body name="b">
      <geom class="visual" type="mesh" mesh="shell"/>
      <geom class="visual" type="mesh" mesh="shared"/>
      <geom class="collision" type="mesh" mesh="shared"/>
      <geom class="visual" type="mesh" mesh="badge" name="badge"/>
      <geom class="visual" type="box" size="0.1 0.1 0.1"/>
    </body>
  </worldbody>
</mujoco>"""


def _meshes_and_geoms(root) -> tuple[list[str], list[str]]:
    meshes = [m.get("name") for m in root.iter("mesh")]
    geoms = [
        g.get("mesh") or g.get("type") for g in root.iter("geom") if g.getparent().tag == "body"
    ]
    return meshes, geoms


def test_compiles_before_the_last_skip_only_meshes_that_draw():
    from mjcfbuild.mjcf.assemble import _drop_drawing_meshes

    root = etree.fromstring(DRAWN)
    _drop_drawing_meshes(root)
    # The named geom may be referred to, the shared mesh collides, the box costs nothing.
    assert _meshes_and_geoms(root) == (["shared", "badge"], ["shared", "badge", "box"])
    # Inputs that give visual geoms mass or contacts leave the model alone.
    for change in ('density="0"/>', 'contype="0"'):
        edited = DRAWN.replace(change, change.replace("0", "1"), 1)
        root = etree.fromstring(edited)
        _drop_drawing_meshes(root)
        assert _meshes_and_geoms(root) == _meshes_and_geoms(etree.fromstring(edited))


def test_a_mesh_mujoco_cannot_hull_is_named_by_its_file_not_its_asset_name(tmp_path):
    """MuJoCo names the mesh by the asset name its URDF import made up ('mesh1'): the build's
    error names the description's file and line instead (stretch_re1's flat STL)."""
    from tests.conftest import run_cli, write

    flat = tmp_path / "urdf/flat.obj"
    write(flat, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
    urdf = two_link_urdf().replace('<box size="0.2 0.2 0.1"/>', '<mesh filename="flat.obj"/>', 1)
    write(tmp_path / "urdf/robot.urdf", urdf)
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: urdf/robot.urdf}\n")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code != 0
    line = next(n for n, text in enumerate(urdf.splitlines(), 1) if "flat.obj" in text)
    error = next(e for e in result.stderr.splitlines() if "error:" in e)
    assert f"robot.urdf:{line}:" in error and "mesh 'flat.obj'" in error, error
    assert "'mesh" not in error.replace("mesh 'flat.obj'", ""), error


def test_a_dae_material_s_glow_is_the_model_material_s_emission(tmp_path):
    """<emission> in the DAE material's own colour becomes MuJoCo's scalar emission."""
    from tests.meshes.test_collada_looks import glowing

    glowing(tmp_path, "0.4 0.2 0")
    urdf = (
        '<robot name="r"><link name="base"><visual><geometry><mesh filename="glow.dae"/>'
        "</geometry></visual></link></robot>"
    )
    _, model = build(urdf, tmp_path)
    assert model.nmat == 1
    assert model.mat_emission[0] == pytest.approx(0.5)
    assert model.mat_rgba[0].tolist() == pytest.approx([0.8, 0.4, 0.0, 1.0])


def test_a_dae_without_a_scene_is_left_out_of_the_model_seen_and_colliding(tmp_path):
    from tests.meshes.test_collada import MATERIAL, QUAD, dae

    (tmp_path / "loose.dae").write_text(
        dae(QUAD + MATERIAL.format(diffuse="<color>1 0 0 1</color>"))
    )
    mesh = '<geometry><mesh filename="loose.dae"/></geometry>'
    box = '<geometry><box size="0.1 0.1 0.1"/></geometry>'
    urdf = (
        f'<robot name="r"><link name="base"><visual>{box}</visual><collision>{box}</collision>'
        f"<visual>{mesh}</visual><collision>{mesh}</collision></link></robot>"
    )
    _, model = build(urdf, tmp_path)
    assert model.ngeom == 2 and model.nmesh == 0  # the boxes


def test_a_visual_mesh_of_one_triangle_is_drawn(tmp_path):
    # urdf-usd-converter's dae_no_normal.urdf: exit 5, MuJoCo naming mjcfbuild's mesh.msh.
    (tmp_path / "tri.obj").write_text("v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nf 1 2 3\n")
    urdf = two_link_urdf(
        extra='<link name="flag"><visual><geometry><mesh filename="tri.obj"/></geometry>'
        '</visual></link><joint name="f" type="fixed"><parent link="arm"/><child link="flag"/>'
        "</joint>"
    )
    _, model = build(urdf, tmp_path)
    assert model.nmesh == 1 and (model.mesh_vertnum[0], model.mesh_facenum[0]) == (4, 1)


def test_a_mesh_too_small_for_mujoco_is_named_by_its_file_and_line(tmp_path):
    # MuJoCo names such a mesh after "too small:" without quotes; the error named its asset.
    tiny = tmp_path / "tiny.obj"
    corners = "v 0 0 0\nv 1e-9 0 0\nv 0 1e-9 0\nv 0 0 1e-9\n"
    tiny.write_text(corners + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    urdf = (
        f'<robot name="r"><link name="a">{INERTIA}\n'
        '<collision><geometry><mesh filename="tiny.obj"/></geometry></collision></link></robot>'
    )
    with pytest.raises(ModelError) as info:
        build(urdf, tmp_path)
    assert (info.value.location.file, info.value.location.line) == ("robot.urdf", 2)
    assert "mesh surface area is too small: mesh 'tiny.obj'" in info.value.message
    assert "<mesh scale>" in (info.value.hint or "")
