"""Collision policies chosen by link and mesh patterns; what each mesh and decomposition needs."""

from __future__ import annotations

from mjcfbuild.collision.policy import (
    Rule,
    choose_collisions,
    decompositions,
    mesh_roles,
)
from mjcfbuild.urdf.model import Geometry, Link, Pose, Robot, Shape

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
