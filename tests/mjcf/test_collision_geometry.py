"""Collision policies end to end: what the built model collides with."""

from __future__ import annotations

import mujoco
import pytest

import mjcfbuild
from tests.conftest import write


def collision_geoms(model, body_name):
    body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body_name)
    result = []
    for geom in range(model.ngeom):
        if model.geom_bodyid[geom] == body and model.geom_group[geom] == 3:
            kind = mujoco.mjtGeom(model.geom_type[geom]).name.removeprefix("mjGEOM_").lower()
            mesh = model.geom_dataid[geom]
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_MESH, mesh) if mesh >= 0 else None
            result.append((kind, name))
    return result


def build_arm(arm, rules: str):
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + rules)
    result = mjcfbuild.build(manifest, jobs=2, check=False)
    return result, mujoco.MjModel.from_xml_path(str(result.robot))


@pytest.mark.parametrize(
    ("policy", "expected"),
    [
        ("authored", [("mesh", "upper_arm")]),
        ("hull", [("mesh", "upper_arm_hull")]),
        ("primitive", [("capsule", None)]),
        ("none", []),
    ],
)
def test_policies_on_a_link_with_an_authored_mesh(arm, policy, expected):
    _, model = build_arm(
        arm, f"collision:\n  rules:\n    - links: [upper_arm_link]\n      policy: {policy}\n"
    )
    assert collision_geoms(model, "upper_arm_link") == expected


def test_visual_policy_collides_with_every_visual_part(arm):
    _, model = build_arm(arm, "collision:\n  default: visual\n")
    # the forearm's OBJ has two materials: one merged collision mesh
    assert collision_geoms(model, "forearm_link") == [("mesh", "forearm_collision")]
    assert collision_geoms(model, "shoulder_link") == [("cylinder", None)]


def test_mesh_pattern_rules(arm):
    _, model = build_arm(
        arm, "collision:\n  rules:\n    - meshes: ['upper_arm.*']\n      policy: hull\n"
    )
    assert collision_geoms(model, "upper_arm_link") == [("mesh", "upper_arm_hull")]
    assert collision_geoms(model, "base_link") == [("cylinder", None)]


def test_switching_policy_reruns_only_the_affected_mesh_and_assembly(arm):
    build_arm(arm, "")
    result, _ = build_arm(
        arm, "collision:\n  rules:\n    - links: [upper_arm_link]\n      policy: hull\n"
    )
    assert sorted(result.ran) == ["assemble", "mesh:upper_arm", "selfcollision"]


def test_identical_files_are_stored_once(tmp_path):
    from tests.conftest import EXAMPLES, INERTIA

    data = (EXAMPLES / "arm" / "meshes" / "finger.stl").read_bytes()
    write(tmp_path / "left" / "finger.stl", "").write_bytes(data)
    write(tmp_path / "right" / "finger.stl", "").write_bytes(data)
    write(
        tmp_path / "robot.urdf",
        f"""<robot name="r"><link name="a">{INERTIA}
          <visual><geometry><mesh filename="left/finger.stl"/></geometry></visual>
          <visual><geometry><mesh filename="right/finger.stl"/></geometry></visual></link></robot>""",
    )
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = mjcfbuild.build(tmp_path / "robot.yaml")
    assert [p.name for p in (tmp_path / "mjcf" / "assets").iterdir()] == ["left_finger.obj"]
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.nmesh == 1 and model.ngeom == 2


def test_a_visual_mesh_without_volume_gets_shell_inertia(tmp_path):
    from tests.conftest import INERTIA

    write(tmp_path / "sticker.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
    write(
        tmp_path / "robot.urdf",
        f'<robot name="r"><link name="a">{INERTIA}<visual><geometry>'
        '<mesh filename="sticker.obj"/></geometry></visual></link></robot>',
    )
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = mjcfbuild.build(tmp_path / "robot.yaml")
    assert 'inertia="shell"' in result.robot.read_text()
    mujoco.MjModel.from_xml_path(str(result.robot))


def test_inertia_policy_fail_names_the_link(cli, tmp_path):
    from tests.conftest import two_link_urdf

    urdf = two_link_urdf().replace(
        '<link name="arm"><inertial><mass value="1"/>',
        '<link name="arm"><inertial><mass value="0"/>',
    )
    write(tmp_path / "robot.urdf", urdf)
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\ninertia: {policy: fail}\n")
    result = cli("build", cwd=tmp_path)
    assert result.code == 4
    assert (
        "robot.urdf:" in result.stderr
        and "link 'arm': moving body with too small a mass" in result.stderr
    )
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    repaired = cli("build", cwd=tmp_path)
    assert repaired.code == 0
    assert "body 'arm': moving body with too small a mass; mass 0 -> mass 0.0001" in repaired.stderr


def test_the_hull_vertex_limit_reaches_mujoco_and_coacd(arm):
    _, model = build_arm(
        arm,
        "meshes: {max_hull_vertices: 16}\n"
        "collision:\n  rules:\n    - meshes: ['upper_arm.*']\n      policy: hull\n",
    )
    import mujoco

    mesh = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_MESH, "upper_arm_hull")
    assert model.mesh_vertnum[mesh] <= 16
    text = (arm / "mjcf" / "example_arm.xml").read_text()
    assert 'maxhullvert="16"' in text


PLATE_OBJ = "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\nf 1 2 3\nf 1 3 4\n"


def flat_collision_robot(tmp_path, rules: str = ""):
    """A robot whose two links collide with flat plates (one file each)."""
    from tests.conftest import INERTIA

    write(tmp_path / "plate.obj", PLATE_OBJ)
    write(tmp_path / "sheet.obj", PLATE_OBJ.replace("v 0.1 0.1 0", "v 0.1 0.2 0"))
    links = "".join(
        f'\n  <link name="{name}">{INERTIA}\n'
        f'    <collision><geometry><mesh filename="{mesh}"/></geometry></collision></link>'
        for name, mesh in (("a", "plate.obj"), ("b", "sheet.obj"))
    )
    joint = (
        '\n  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    )
    write(tmp_path / "robot.urdf", f'<robot name="r">{links}{joint}\n</robot>\n')
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + rules)


@pytest.mark.parametrize("policy", ["authored", "hull", "decompose"])
def test_every_flat_collision_mesh_is_named_at_once_with_the_rule_to_add(cli, tmp_path, policy):
    flat_collision_robot(tmp_path, f"collision: {{default: {policy}}}\n")
    result = cli("build", "--no-check", cwd=tmp_path)
    assert result.code == 5, result.stderr
    error = [line for line in result.stderr.splitlines() if "error:" in line]
    assert len(error) == 1 and "Traceback" not in result.stderr
    assert (
        "robot.urdf:3: 2 collision meshes are flat (their vertices lie in a plane): "
        "'plate.obj' of link 'a', 'sheet.obj' of link 'b' (line 5)" in error[0]
    )
    assert '{meshes: ["plate.obj", "sheet.obj"], policy: primitive}' in error[0]


def test_the_primitive_policy_gives_a_flat_mesh_a_thin_box(cli, tmp_path):
    flat_collision_robot(
        tmp_path,
        "collision:\n  rules:\n    - {meshes: [plate.obj, sheet.obj], policy: primitive}\n",
    )
    result = cli("build", "--no-check", cwd=tmp_path)
    assert result.code == 0, result.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "r.xml"))
    assert collision_geoms(model, "a") == [("box", None)]
    assert 2e-4 < min(model.geom_size[model.geom_group == 3][0]) < 1e-3


def test_a_fixed_robot_without_any_collision_geometry_is_warned_about(tmp_path):
    """A hand whose URDF has no <collision> built and passed without a word: nothing of it
    touches anything (a floating robot's stand already says so)."""
    import re

    from tests.conftest import run_cli, simple_manifest, two_link_urdf

    drawn_only = re.sub(r"<collision>.*?</collision>", "", two_link_urdf(), flags=re.S)
    write(tmp_path / "robot.urdf", drawn_only)
    simple_manifest(tmp_path)
    built = run_cli("build", "--no-check", cwd=tmp_path)
    assert built.code == 0, built.stderr
    assert "the model has no collision geometry (the URDF has no <collision>" in built.stderr
    assert "set collision.default: visual" in built.stderr
    simple_manifest(tmp_path, extra="collision: {default: visual}\n")
    again = run_cli("build", "--no-check", cwd=tmp_path)
    assert again.code == 0 and "no collision geometry" not in again.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mjcf" / "robot.xml"))
    assert any(model.geom_contype[g] for g in range(model.ngeom))
