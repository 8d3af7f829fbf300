"""The training variant of the example quadruped: built by the real build, read by MuJoCo."""

from __future__ import annotations

import functools
import json

import mujoco
import numpy as np
import pytest

import mjcfbuild
from tests.conftest import copy_example, run_cli

PRIMITIVES = {
    int(mujoco.mjtGeom.mjGEOM_SPHERE),
    int(mujoco.mjtGeom.mjGEOM_CAPSULE),
    int(mujoco.mjtGeom.mjGEOM_BOX),
}
SHINS = ["front_left_shin", "front_right_shin", "rear_left_shin", "rear_right_shin"]


def quadruped(tmp_path, training: str, extra: str = ""):
    folder = copy_example("quadruped", tmp_path)
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text() + training + extra)
    return folder


def build(folder):
    return mjcfbuild.build(folder / "robot.yaml", jobs=1, check=False)


def colliding(model):
    """The collision geoms (group 3), whether they meet the floor or only explicit pairs."""
    return [g for g in range(model.ngeom) if model.geom_group[g] == 3]


def self_contacts(model):
    """The body pairs MuJoCo considers for contact, as its filters decide: contype/conaffinity,
    parent and child, <exclude>, plus explicit pairs."""
    name = lambda b: mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b)  # noqa: E731
    excluded = {frozenset((s >> 16, s & 0xFFFF)) for s in model.exclude_signature}
    pairs = set()
    for i in range(model.ngeom):
        for j in range(i + 1, model.ngeom):
            first, second = model.geom_bodyid[i], model.geom_bodyid[j]
            if first == second or frozenset((first, second)) in excluded:
                continue
            if model.body_parentid[first] == second or model.body_parentid[second] == first:
                continue
            if model.geom_contype[i] & model.geom_conaffinity[j] or (
                model.geom_contype[j] & model.geom_conaffinity[i]
            ):
                pairs.add(tuple(sorted((name(first), name(second)))))
    for p in range(model.npair):
        pairs.add(
            tuple(sorted((body(model, model.pair_geom1[p]), body(model, model.pair_geom2[p]))))
        )
    return pairs


def body(model, geom):
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[geom])


def test_variant_and_scene_beside_the_model_and_only_its_task_reruns(tmp_path):
    folder = quadruped(tmp_path, "  training: true\n")
    assert "training" in build(folder).ran
    out = folder / "mjcf"
    scene = mujoco.MjModel.from_xml_path(str(out / "scene_mjx.xml"))
    assert b'file="example_quadruped_mjx.xml"' in (out / "scene_mjx.xml").read_bytes()
    assert (scene.opt.iterations, scene.opt.ls_iterations) == (1, 5)  # a GPU's defaults
    # The shin mesh is only drawn (the legs collide with authored primitives): an edit to it
    # leaves the variant, which refers to the same asset file, as it is.
    nudge(folder / "meshes" / "shin.stl")
    assert sorted(build(folder).ran) == ["assemble", "mesh:shin"]
    assert build(folder).ran == []


def test_an_edit_to_a_colliding_mesh_reruns_its_tasks_and_the_variant(tmp_path):
    folder = quadruped(tmp_path, "  training: true\n", "collision:\n  default: visual\n")
    build(folder)
    variant = folder / "mjcf" / "example_quadruped_mjx.xml"
    before = variant.read_bytes()
    nudge(folder / "meshes" / "shin.stl", scale=1.5)
    # The mesh's task, the matrix and the model (its collision hull changed), the variant.
    assert sorted(build(folder).ran) == ["assemble", "mesh:shin", "selfcollision", "training"]
    assert variant.read_bytes() != before


def nudge(mesh, scale=None):
    """Move the first vertex of a binary STL (or scale every coordinate)."""
    import numpy as np

    data = bytearray(mesh.read_bytes())
    if scale is None:
        data[84 + 12] ^= 0x01
    else:
        count = int(np.frombuffer(bytes(data[80:84]), dtype="<u4")[0])
        records = np.frombuffer(
            bytes(data[84:]),
            dtype=np.dtype(
                [("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")]
            ),
            count=count,
        ).copy()
        records["vertices"] *= scale
        data[84:] = records.tobytes()
    mesh.write_bytes(bytes(data))


def test_geoms_are_primitives_and_contacts_are_what_the_rules_say(tmp_path):
    folder = quadruped(tmp_path, "  training:\n    self_contacts: true\n")
    build(folder)
    out = folder / "mjcf"
    model = mujoco.MjModel.from_xml_path(str(out / "example_quadruped_mjx.xml"))
    geoms = colliding(model)
    assert geoms and all(model.geom_type[g] in PRIMITIVES for g in geoms)
    assert int(mujoco.mjtGeom.mjGEOM_CYLINDER) not in {
        int(t) for t in model.geom_type
    }  # authored ones became capsules
    # The floor (contype 1): the feet (touching at home, and the leaves of the tree).
    assert sorted(body(model, g) for g in geoms if model.geom_conaffinity[g] & 1) == SHINS
    assert not any(model.geom_contype[g] & 1 for g in range(model.ngeom))
    # Self contacts: the matrix's "sometimes" pairs between bodies not joined by one joint.
    matrix = json.loads((out / ".mjcfbuild" / "self_collision.json").read_text())
    parents = {
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b): mujoco.mj_id2name(
            model, mujoco.mjtObj.mjOBJ_BODY, model.body_parentid[b]
        )
        for b in range(1, model.nbody)
    }
    expected = {
        tuple(sorted((v["body1"], v["body2"])))
        for v in matrix["pairs"]
        if v["reason"] == "sometimes"
        and parents[v["body1"]] != v["body2"]
        and parents[v["body2"]] != v["body1"]
    }
    assert expected and self_contacts(model) == expected and model.npair == 0


def test_by_default_only_the_floor_and_only_through_the_soles(tmp_path):
    folder = quadruped(tmp_path, "  training: true\n")
    build(folder)
    model = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "example_quadruped_mjx.xml"))
    assert self_contacts(model) == set() and model.nexclude == 0
    assert scene_solver(folder) == (int(mujoco.mjtSolver.mjSOL_NEWTON), 1, 5)
    assert json.loads((folder / "mjcf" / ".mjcfbuild" / "training.json").read_text())["solver"] == {
        "device": "gpu",
        "solver": "newton",
        "iterations": 1,
        "ls_iterations": 5,
    }
    manifest = folder / "robot.yaml"
    original = manifest.read_text()
    manifest.write_text(original.replace("training: true", "training:\n    device: cpu"))
    assert build(folder).ran == ["training"]
    assert scene_solver(folder) == (int(mujoco.mjtSolver.mjSOL_CG), 2, 4)
    # A solver given brings its own iteration caps; a cap given keeps its value.
    text = original.replace("training: true", "training:\n    device: cpu\n    solver: newton")
    manifest.write_text(text)
    build(folder)
    assert scene_solver(folder) == (int(mujoco.mjtSolver.mjSOL_NEWTON), 1, 5)
    manifest.write_text(text + "    ls_iterations: 9\n")
    build(folder)
    assert scene_solver(folder) == (int(mujoco.mjtSolver.mjSOL_NEWTON), 1, 9)


def scene_solver(folder):
    """The variant scene's solver and its iteration caps."""
    scene = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "scene_mjx.xml"))
    return int(scene.opt.solver), int(scene.opt.iterations), int(scene.opt.ls_iterations)


LEG = """<mujoco>
  <worldbody>
    <body name="base" pos="0 0 0.28">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.05"/>
      <body name="shin" pos="0 0 -0.05">
        <joint axis="0 1 0"/>
        <geom name="shin" type="box" size="0.01 0.01 0.1" pos="0 0 -0.1"/>
        <geom name="foot" type="sphere" size="0.03" pos="0 0 -0.2"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_a_link_on_the_floor_meets_it_only_through_its_sole(tmp_path):
    from mjcfbuild.training.variant import VariantSettings, build_variant

    path = tmp_path / "leg.xml"
    path.write_text(LEG)
    variant = build_variant(str(path), [], VariantSettings())
    model = mujoco.MjModel.from_xml_string(variant.xml)
    floor = {model.geom(g).name for g in range(model.ngeom) if model.geom_conaffinity[g] & 1}
    # The foot sphere reaches the floor at home; the box along the shin ends 30 mm above it.
    assert variant.floor == ["shin"] and floor == {"shin_collision_1"}
    assert model.geom("shin_collision_1").type == mujoco.mjtGeom.mjGEOM_SPHERE
    # A link added to the floor that does not touch it at home keeps all of its geoms.
    added = build_variant(str(path), [], VariantSettings(floor_add=("base",)))
    model = mujoco.MjModel.from_xml_string(added.xml)
    floor = {model.geom(g).name for g in range(model.ngeom) if model.geom_conaffinity[g] & 1}
    assert floor == {"shin_collision_1", "base_collision"}


def test_floor_rules_add_and_remove_links(tmp_path):
    rules = (
        "  training:\n    floor_contacts:\n      add: [trunk]\n      remove: [front_left_shin]\n"
        "    self_contacts: false\n"
    )
    folder = quadruped(tmp_path, rules)
    build(folder)
    model = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "example_quadruped_mjx.xml"))
    on_floor = sorted(body(model, g) for g in colliding(model) if model.geom_conaffinity[g] & 1)
    assert on_floor == ["front_right_shin", "rear_left_shin", "rear_right_shin", "trunk"]
    assert self_contacts(model) == set()


def test_meshes_become_primitives_or_hulls_under_the_cap(tmp_path):
    # Every link collides with its visual mesh in the full model; a fit of 1 refuses
    # every primitive that is not exactly the hull, so the variant falls back to capped hulls.
    settings = "  training:\n    primitive_fit: 1.0\n    max_hull_vertices: 8\n"
    folder = quadruped(tmp_path, settings, "collision:\n  default: visual\n")
    build(folder)
    model = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "example_quadruped_mjx.xml"))
    hulls = [g for g in colliding(model) if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH]
    assert hulls
    for geom in colliding(model):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_MESH:
            assert model.mesh_vertnum[model.geom_dataid[geom]] <= 8
        else:
            assert model.geom_type[geom] in PRIMITIVES
    # With the default fit the same meshes become primitives.
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("primitive_fit: 1.0", "primitive_fit: 2.0"))
    build(folder)
    model = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "example_quadruped_mjx.xml"))
    assert all(model.geom_type[g] in PRIMITIVES for g in colliding(model))


@pytest.mark.parametrize(
    ("settings", "where"),
    [
        ("  training:\n    floor_contacts:\n      add: [no_such_link]\n", "robot.yaml:18:"),
        ("  training:\n    iterations: 0\n", "robot.yaml:17:"),
        ("  training:\n    timestep: -0.001\n", "robot.yaml:17:"),
        ("  training:\n    solver: pgs\n", "robot.yaml:17:"),
        ("  training:\n    device: tpu\n", "robot.yaml:17:"),
    ],
)
def test_bad_settings_are_one_line_with_the_robot_yaml_line_and_exit_3(tmp_path, settings, where):
    folder = quadruped(tmp_path, settings)
    result = run_cli("build", str(folder / "robot.yaml"), "--no-check")
    assert result.code == 3, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) <= 2 and where in lines[0], result.stderr


SMALL = """<mujoco>
  <worldbody>
    <body name="base" pos="0 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.05"/>
      <body name="leg" pos="0 0 -0.05">
        <joint name="knee" axis="0 1 0" frictionloss="0.3"/>
        <geom type="cylinder" size="0.01 0.02" pos="0 0 -0.02"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_frictionloss_goes_unless_kept_and_cylinders_become_capsules(tmp_path):
    from mjcfbuild.training.variant import VariantSettings, build_variant

    path = tmp_path / "small.xml"
    path.write_text(SMALL)
    variant = build_variant(str(path), [], VariantSettings())
    model = mujoco.MjModel.from_xml_string(variant.xml)
    assert model.dof_frictionloss.max() == 0
    assert variant.geoms == {"base": ["box"], "leg": ["capsule"]}
    assert variant.floor == ["leg"]
    assert any("frictionloss removed from 1 joints" in note for note in variant.notes)
    kept = build_variant(str(path), [], VariantSettings(frictionloss=True))
    assert mujoco.MjModel.from_xml_string(kept.xml).dof_frictionloss.max() == pytest.approx(0.3)


OVERLAP = """<mujoco>
  <worldbody>
    <body name="base" pos="0 0 0.5">
      <freejoint/>
      <geom type="sphere" size="0.1"/>
      <body name="upper" pos="0.3 0 0">
        <joint axis="0 1 0"/>
        <geom type="capsule" size="0.02 0.05" pos="0.1 0 0"/>
        <body name="hand" pos="0.2 0 0">
          <joint axis="0 1 0"/>
          <geom type="sphere" size="0.03"/>
        </body>
      </body>
      <body name="tail" pos="-0.12 0 0">
        <joint axis="0 1 0"/>
        <geom type="sphere" size="0.03"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_self_pairs_that_overlap_at_home_in_the_variant_are_left_out(tmp_path):
    from mjcfbuild.training.variant import VariantSettings, build_variant

    path = tmp_path / "overlap.xml"
    path.write_text(OVERLAP)
    verdicts = [
        {"body1": "base", "body2": "hand", "reason": "sometimes", "exclude": False},
        {"body1": "base", "body2": "tail", "reason": "sometimes", "exclude": False},  # adjacent
        {"body1": "hand", "body2": "tail", "reason": "sometimes", "exclude": False},
    ]
    with_pairs = VariantSettings(self_contacts=True)
    variant = build_variant(str(path), verdicts, with_pairs)
    assert variant.pairs == [("base", "hand"), ("hand", "tail")]
    # The tail overlaps the base at home, but they are parent and child: no pair at all. Move
    # the tail into the hand at home, and that pair goes, with a note.
    path.write_text(OVERLAP.replace('name="tail" pos="-0.12 0 0"', 'name="tail" pos="0.5 0 0"'))
    variant = build_variant(str(path), verdicts, with_pairs)
    assert variant.pairs == [("base", "hand")]
    assert "hand and tail overlap at home in the variant: no pair" in variant.notes
    model = mujoco.MjModel.from_xml_string(variant.xml)
    assert self_contacts(model) == {("base", "hand")}


def test_the_variant_is_the_same_bytes_in_another_folder_and_holds_no_paths(tmp_path):
    first = quadruped(tmp_path / "a", "  training: true\n", "collision:\n  default: visual\n")
    second = quadruped(tmp_path / "b", "  training: true\n", "collision:\n  default: visual\n")
    build(first)
    build(second)
    for name in ("example_quadruped_mjx.xml", "scene_mjx.xml"):
        data = (first / "mjcf" / name).read_bytes()
        assert data == (second / "mjcf" / name).read_bytes()
        assert str(tmp_path).encode() not in data


USER_SCENE = """<mujoco model="my scene">
  <include file="example_quadruped.xml"/>
  <worldbody><geom name="ground" type="plane" size="0 0 0.05"/></worldbody>
</mujoco>
"""


def test_a_user_scene_file_includes_the_variant_in_its_scene(tmp_path):
    folder = quadruped(tmp_path, "  training: true\n", "scene:\n  file: my_scene.xml\n")
    (folder / "my_scene.xml").write_text(USER_SCENE)
    build(folder)
    scene = (folder / "mjcf" / "scene_mjx.xml").read_text()
    assert scene == USER_SCENE.replace("example_quadruped.xml", "example_quadruped_mjx.xml")
    assert mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "scene_mjx.xml")).opt.iterations == 1
    # A scene file that does not include the model by its file name: one line, exit 4.
    (folder / "my_scene.xml").write_text(USER_SCENE.replace("example_quadruped.xml", "robot.xml"))
    result = run_cli("build", "--no-check", str(folder / "robot.yaml"))
    assert result.code == 4, result.stderr
    assert "my_scene.xml" in result.stderr and "does not include example_quadruped.xml" in (
        result.stderr
    )


def test_dcmotor_servos_become_position_servos_with_the_same_gains_unless_kept(tmp_path):
    folder = quadruped(tmp_path, "  training: true\n")
    build(folder)
    out = folder / "mjcf"
    full = mujoco.MjModel.from_xml_path(str(out / "example_quadruped.xml"))
    variant = mujoco.MjModel.from_xml_path(str(out / "example_quadruped_mjx.xml"))
    dcmotor = int(mujoco.mjtGain.mjGAIN_DCMOTOR)
    assert full.nu == variant.nu > 0 and all(full.actuator_gaintype == dcmotor)
    assert all(variant.actuator_gaintype == int(mujoco.mjtGain.mjGAIN_FIXED))
    assert all(variant.actuator_biastype == int(mujoco.mjtBias.mjBIAS_AFFINE))
    kp, kv = full.actuator_gainprm[:, 4], full.actuator_gainprm[:, 6]  # the controller's gains
    same = functools.partial(np.allclose, rtol=1e-5, atol=0)  # MuJoCo writes 6 digits
    assert same(variant.actuator_gainprm[:, 0], kp)
    assert same(variant.actuator_biasprm[:, 1], -kp) and same(variant.actuator_biasprm[:, 2], -kv)
    assert same(variant.actuator_forcerange, full.actuator_forcerange)
    assert same(variant.actuator_ctrlrange, full.actuator_ctrlrange)
    assert same(variant.dof_armature, full.dof_armature)  # the rotor inertia stays
    record = json.loads((out / ".mjcfbuild" / "training.json").read_text())
    assert any("<dcmotor> servos are <position> servos" in note for note in record["notes"])
    manifest = folder / "robot.yaml"
    text = manifest.read_text().replace("training: true", "training:\n    dcmotor: true")
    manifest.write_text(text)
    build(folder)
    kept = mujoco.MjModel.from_xml_path(str(out / "example_quadruped_mjx.xml"))
    assert all(kept.actuator_gaintype == dcmotor)
    assert same(kept.actuator_gainprm, full.actuator_gainprm)
