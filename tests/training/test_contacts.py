"""The contact rules of the training variant, on a small tree."""

from __future__ import annotations

from mjcfbuild.training.contacts import floor_bodies, leaves, self_pairs

# base -> hip -> leg -> foot, base -> arm -> hand -> imu (no geometry)
PARENTS = {
    "base": None,
    "hip": "base",
    "leg": "hip",
    "foot": "leg",
    "arm": "base",
    "hand": "arm",
    "imu": "hand",
}
COLLIDING = {"base", "leg", "foot", "arm", "hand"}


def test_leaves_are_colliding_bodies_without_colliding_descendants():
    assert leaves(PARENTS, COLLIDING) == {"foot", "hand"}


def test_floor_takes_touching_bodies_and_leaves_then_the_rules():
    assert floor_bodies(PARENTS, COLLIDING, touching={"foot", "base"}) == ["base", "foot", "hand"]
    chosen = floor_bodies(PARENTS, COLLIDING, {"foot"}, add=["leg"], remove=["hand"])
    assert chosen == ["foot", "leg"]


def test_only_sometimes_pairs_between_non_adjacent_colliding_bodies():
    verdicts = [
        {"body1": "leg", "body2": "hand", "reason": "sometimes", "exclude": False},
        {"body1": "foot", "body2": "leg", "reason": "sometimes", "exclude": False},  # adjacent
        {"body1": "base", "body2": "foot", "reason": "never", "exclude": False},
        {"body1": "base", "body2": "hand", "reason": "home", "exclude": True},
        {"body1": "hip", "body2": "hand", "reason": "sometimes", "exclude": False},  # no geometry
        {"body1": "hand", "body2": "foot", "reason": "sometimes", "exclude": False},
    ]
    assert self_pairs(verdicts, PARENTS, COLLIDING) == [("foot", "hand"), ("hand", "leg")]
