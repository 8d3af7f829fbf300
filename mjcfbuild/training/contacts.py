"""Which contacts the training variant keeps: the rules, apart from MuJoCo.

Batched engines pay for every candidate geom pair in every world at every step, so the
variant keeps only the contacts a policy learns from:

* the floor, with the links that touch it at home (feet, wheels, a base on the ground) and
  the end effectors (leaves of the tree: feet, fingertips), plus links the user adds, minus
  links the user removes;
* between the robot's own links, the pairs the self-collision matrix found touching
  *sometimes* in random configurations, when the two links are not joined by one joint
  (MuJoCo filters parent-child contacts; an explicit pair would bypass that filter).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping


def leaves(parents: Mapping[str, str | None], colliding: Iterable[str]) -> set[str]:
    """Colliding bodies none of whose descendants collide: the ends of the kinematic tree.

    ``parents`` maps every body to its parent (None for a child of the world). A body with
    only geometry-less children (an IMU frame, a tool frame) still counts as a leaf.
    """
    colliding = set(colliding)
    inner: set[str] = set()
    for body in colliding:
        parent = parents.get(body)
        while parent is not None:
            inner.add(parent)
            parent = parents.get(parent)
    return colliding - inner


def floor_bodies(
    parents: Mapping[str, str | None],
    colliding: Iterable[str],
    touching: Iterable[str],
    add: Iterable[str] = (),
    remove: Iterable[str] = (),
) -> list[str]:
    """The bodies whose collision geometry meets the floor, sorted."""
    colliding = set(colliding)
    chosen = (set(touching) & colliding) | leaves(parents, colliding) | set(add)
    return sorted((chosen - set(remove)) & colliding)


def self_pairs(
    verdicts: Iterable[Mapping], parents: Mapping[str, str | None], colliding: Iterable[str]
) -> list[tuple[str, str]]:
    """The body pairs that keep colliding with each other: the matrix's ``sometimes`` pairs
    that it does not exclude, between bodies that both collide and are not parent and child."""
    colliding = set(colliding)
    pairs = set()
    for verdict in verdicts:
        first, second = verdict["body1"], verdict["body2"]
        if verdict["reason"] != "sometimes" or verdict["exclude"]:
            continue
        if first not in colliding or second not in colliding:
            continue
        if parents.get(first) == second or parents.get(second) == first:
            continue
        pairs.add((min(first, second), max(first, second)))
    return sorted(pairs)
