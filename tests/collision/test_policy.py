"""Collision policies chosen by link and mesh patterns; what each mesh and decomposition needs."""

from __future__ import annotations

from dataclasses import replace

import pytest

from mjcfbuild.collision.policy import (
    POLICIES,
    POLICY_NAMES,
    CollisionChoice,
    Rule,
    choose_collisions,
    collision_policy,
    decompositions,
    mesh_roles,
)
from mjcfbuild.errors import InternalError, ManifestError
from mjcfbuild.manifest.loading import load_manifest
from mjcfbuild.manifest.schema import manifest_schema
from mjcfbuild.mjcf.bodies import build_bodies
from mjcfbuild.mjcf.prepared import prepare
from mjcfbuild.urdf.model import Geometry, Link, Pose, Robot, Shape
from tests.conftest import ROOT, write

DEFAULTS = {"threshold": 0.05, "seed": 0}


def mesh_shape(role, index, mesh_id):
    geometry = Geometry(
        "mesh", uri=f"package://p/{mesh_id}.stl", path=f"/p/{mesh_id}.stl", mesh_id=mesh_id
    )
    return Shape(role, index, Pose(), geometry)


def box_shape(role, index):
    return Shape(role, index, Pose(), Geometry("box", (1, 1, 1)))


def robot():
    return Robot(
        "r",
        [
            Link(
                "base",
                visuals=[mesh_shape("visual", 0, "base")],
                collisions=[box_shape("collision", 0)],
            ),
            Link(
                "arm",
                visuals=[mesh_shape("visual", 0, "arm")],
                collisions=[mesh_shape("collision", 0, "arm_c")],
            ),
            Link("hand", visuals=[mesh_shape("visual", 0, "hand"), box_shape("visual", 1)]),
        ],
        [],
    )


def summary(choices):
    return [(c.link, c.role, c.index, c.policy) for c in choices]


def test_default_authored_keeps_only_urdf_collisions():
    choices = choose_collisions(robot(), "authored", [], DEFAULTS)
    assert summary(choices) == [
        ("base", "collision", 0, "authored"),
        ("arm", "collision", 0, "authored"),
    ]


def test_visual_policy_uses_visual_shapes():
    choices = choose_collisions(robot(), "visual", [], DEFAULTS)
    assert summary(choices) == [
        ("base", "visual", 0, "visual"),
        ("arm", "visual", 0, "visual"),
        ("hand", "visual", 0, "visual"),
        ("hand", "visual", 1, "visual"),
    ]


def test_transforming_policies_use_collisions_if_any_else_visuals():
    choices = choose_collisions(robot(), "hull", [], DEFAULTS)
    assert summary(choices) == [
        ("base", "collision", 0, "hull"),
        ("arm", "collision", 0, "hull"),
        ("hand", "visual", 0, "hull"),
        ("hand", "visual", 1, "hull"),
    ]


def test_first_matching_rule_wins_links_and_meshes():
    rules = [
        Rule("none", links=("base",)),
        Rule("decompose", meshes=("hand.stl",), decompose=(("seed", 0), ("threshold", 0.02))),
        Rule("primitive", links=("h*",)),
    ]
    choices = choose_collisions(robot(), "authored", rules, DEFAULTS)
    assert summary(choices) == [
        ("arm", "collision", 0, "authored"),
        ("hand", "visual", 0, "decompose"),
        ("hand", "visual", 1, "primitive"),
    ]
    assert choices[1].decompose_params == {"seed": 0, "threshold": 0.02}


def test_mesh_roles_and_decomposition_names():
    rules = [Rule("decompose", links=("arm",), decompose=(("threshold", 0.1),))]
    choices = choose_collisions(robot(), "hull", rules, DEFAULTS)
    roles = mesh_roles(robot(), choices)
    assert roles == {
        "arm": ["visual"],
        "arm_c": ["collision"],
        "base": ["visual"],
        "hand": ["hull", "visual"],
    }
    assert decompositions(robot(), choices) == {"arm_c": ("arm_c", {"threshold": 0.1})}


def test_one_mesh_with_two_parameter_sets_gets_two_named_decompositions():
    shared = Robot(
        "r",
        [
            Link("a", collisions=[mesh_shape("collision", 0, "m")]),
            Link("b", collisions=[mesh_shape("collision", 0, "m")]),
        ],
        [],
    )
    rules = [
        Rule("decompose", links=("a",), decompose=(("threshold", 0.1),)),
        Rule("decompose", links=("b",), decompose=(("threshold", 0.2),)),
    ]
    names = decompositions(shared, choose_collisions(shared, "authored", rules, DEFAULTS))
    assert len(names) == 2 and all(name.startswith("m-") for name in names)


def test_an_unknown_policy_is_an_error_everywhere_never_decompose():
    with pytest.raises(InternalError, match="unknown collision policy 'decompse'"):
        collision_policy("decompse")
    with pytest.raises(InternalError) as info:
        choose_collisions(robot(), "decompse", [], DEFAULTS)
    assert "(known: authored, visual, hull, decompose, primitive, none)" in info.value.one_line()
    typo = CollisionChoice("arm", "collision", 0, "decompse")
    for use in (mesh_roles, decompositions):
        with pytest.raises(InternalError, match="decompse"):
            use(robot(), [typo])
    # the dispatch that makes the geoms: a box needs no mesh product, so only the name can fail
    base = CollisionChoice("base", "collision", 0, "decompse")
    bodies = build_bodies(robot(), fuse_static=False)
    with pytest.raises(InternalError, match="decompse"):
        prepare("r", bodies, {}, {}, [base], [], {}, "r.urdf", visuals=False)
    assert prepare(
        "r", bodies, {}, {}, [replace(base, policy="hull")], [], {}, "r.urdf", visuals=False
    ).geoms


def test_robot_yaml_names_exactly_the_registered_policies(tmp_path):
    schema = manifest_schema()["$defs"]
    for field in (
        schema["CollisionRule"]["properties"]["policy"],
        schema["CollisionSettings"]["properties"]["default"],
    ):
        assert field["enum"] == list(POLICY_NAMES)
        assert all(
            f"{name}: {POLICIES[name].description}" in field["description"] for name in POLICY_NAMES
        )
    write(
        tmp_path / "robot.yaml", "name: r\nsource: {urdf: r.urdf}\ncollision: {default: decompse}\n"
    )
    with pytest.raises(ManifestError) as info:
        load_manifest(tmp_path / "robot.yaml")
    assert (
        "'decompse' is not allowed; did you mean 'decompose'? use one of 'authored', 'visual'"
        in info.value.one_line()
    )


def test_the_docs_table_is_the_registry():
    text = (ROOT / "docs" / "collision.md").read_text()
    rows = [line for line in text.splitlines() if line.startswith("| `")]
    assert rows == [f"| `{p.name}` | {p.description} |" for p in POLICIES.values()]
