"""Which geometry each link collides with, chosen by name patterns in robot.yaml.

Every visual and every authored collision of a link is a *candidate*. Each candidate gets the
policy of the first rule that matches it (by link name and/or mesh name), or the default.
:data:`POLICIES` is the one list of policies: each has its name, its description (robot.yaml's
schema and the docs say it), which of a link's shapes it turns into collision geometry, what it
needs of a mesh's task and the function that makes the geoms of a mesh. robot.yaml's policy
names, the mesh roles, the decompositions and the geoms in ``mjcf.prepared`` all come from it.
"""

from __future__ import annotations

import fnmatch
import hashlib
import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import PurePath
from typing import Any, Literal, Protocol

from mjcfbuild.errors import InternalError
from mjcfbuild.urdf.model import Link, Robot, Shape


class MeshCollision(Protocol):
    """The collision geoms one mesh shape can become (``mjcf.prepared`` makes them)."""

    def mesh(self) -> list[Any]:
        """The mesh itself (its collision product: simplified within the face budget)."""

    def hull(self) -> list[Any]:
        """The mesh's convex hull."""

    def fitted_primitive(self) -> list[Any]:
        """The box, capsule, cylinder or sphere that fits the mesh best."""

    def decomposition(self) -> list[Any]:
        """The parts of the mesh's CoACD decomposition (or its hull, where close enough)."""


@dataclass(frozen=True)
class CollisionPolicy:
    """One collision policy: what it is called and says, and what it does."""

    name: str
    description: str  # robot.yaml's schema and docs/collision.md say it
    # The shapes of a link it turns into collision geometry: the authored collisions, the
    # visuals, the link's source shapes (its collisions if it has any, else its visuals), none.
    shapes: Literal["collision", "visual", "source", "none"]
    # What the mesh task must make of a mesh this policy collides with ("collision": the
    # collision mesh, "hull": its convex hull; None for a policy that takes no shape).
    mesh_role: Literal["collision", "hull"] | None
    geoms: Callable[[MeshCollision], list[Any]]  # the geoms of one mesh shape
    coacd: bool = False  # whether it takes CoACD parameters (collision.decompose)

    def takes(self, shape: Shape, source_role: str) -> bool:
        """Whether ``shape`` (of a link whose source shapes are ``source_role``) collides."""
        if self.shapes == "source":
            return shape.role == source_role
        return shape.role == self.shapes


POLICIES: dict[str, CollisionPolicy] = {
    policy.name: policy
    for policy in (
        CollisionPolicy(
            "authored",
            "the URDF's collision elements",
            "collision",
            "collision",
            lambda mesh: mesh.mesh(),
        ),
        CollisionPolicy(
            "visual",
            "the visual shapes, as the mujoco_ros2_control converter did",
            "visual",
            "collision",
            lambda mesh: mesh.mesh(),
        ),
        CollisionPolicy(
            "hull",
            "each mesh's convex hull",
            "source",
            "hull",
            lambda mesh: mesh.hull(),
        ),
        CollisionPolicy(
            "decompose",
            "each mesh's CoACD convex decomposition (its hull where close enough)",
            "source",
            "collision",
            lambda mesh: mesh.decomposition(),
            coacd=True,
        ),
        CollisionPolicy(
            "primitive",
            "the box, capsule, cylinder or sphere that fits each mesh best",
            "source",
            "hull",
            lambda mesh: mesh.fitted_primitive(),
        ),
        CollisionPolicy("none", "no collision geometry", "none", None, lambda mesh: []),
    )
}
POLICY_NAMES = tuple(POLICIES)


def collision_policy(name: str) -> CollisionPolicy:
    """The policy called ``name``; any other name is an error, never a default."""
    try:
        return POLICIES[name]
    except KeyError:
        raise InternalError(
            f"unknown collision policy {name!r}", hint=f"known: {', '.join(POLICY_NAMES)}"
        ) from None


def policies_described() -> str:
    """Every policy with its description, for robot.yaml's schema."""
    listed = "; ".join(f"{policy.name}: {policy.description}" for policy in POLICIES.values())
    sourced = [policy.name for policy in POLICIES.values() if policy.shapes == "source"]
    return (
        f"{listed}. {', '.join(sourced)} take a link's collision shapes, or its visuals where "
        "it has none"
    )


@dataclass(frozen=True)
class Rule:
    """A collision rule: patterns, a policy and (for decompose) the CoACD parameters."""

    policy: str
    links: tuple[str, ...] = ()
    meshes: tuple[str, ...] = ()
    decompose: tuple[tuple[str, object], ...] = ()


@dataclass(frozen=True)
class CollisionChoice:
    """One collision geometry to build: from which shape of which link, and how."""

    link: str
    role: str
    index: int
    policy: str
    decompose: tuple[tuple[str, object], ...] = ()

    @property
    def decompose_params(self) -> dict:
        """The CoACD parameters as a dict."""
        return dict(self.decompose)

    def to_dict(self) -> dict:
        """The choice as JSON-ready data."""
        return {
            "link": self.link,
            "role": self.role,
            "index": self.index,
            "policy": self.policy,
            "decompose": [list(item) for item in self.decompose],
        }

    @classmethod
    def from_dict(cls, data: dict) -> CollisionChoice:
        """The choice :meth:`to_dict` gave."""
        return cls(
            data["link"],
            data["role"],
            data["index"],
            data["policy"],
            tuple((str(key), value) for key, value in data["decompose"]),
        )


def decompose_id(mesh_id: str, params: dict) -> str:
    """A stable short id of one decomposition of a mesh with given parameters."""
    digest = hashlib.sha1(json.dumps(params, sort_keys=True).encode()).hexdigest()[:8]
    return f"{mesh_id}-{digest}"


def rules_from_dicts(rules: list[dict]) -> list[Rule]:
    """Rules from their plain form (the manifest's ``collision.effective_rules``)."""
    return [
        Rule(
            policy=collision_policy(rule["policy"]).name,
            links=tuple(rule["links"]),
            meshes=tuple(rule["meshes"]),
            decompose=tuple(sorted(rule["decompose"].items())),
        )
        for rule in rules
    ]


def choose_collisions(
    robot: Robot, default: str, rules: list[Rule], default_decompose: dict
) -> list[CollisionChoice]:
    """Every collision geometry of the model, in link order."""
    choices = []
    for link in robot.links:
        source_role = "collision" if link.collisions else "visual"
        for shape in link.collisions + link.visuals:
            name, params = _policy_for(link, shape, default, rules, default_decompose)
            policy = collision_policy(name)
            if policy.takes(shape, source_role):
                decompose = tuple(sorted(params.items())) if policy.coacd else ()
                choices.append(
                    CollisionChoice(link.name, shape.role, shape.index, policy.name, decompose)
                )
    return choices


def _policy_for(link: Link, shape: Shape, default: str, rules: list[Rule], params: dict):
    for rule in rules:
        if rule.links and not any(fnmatch.fnmatchcase(link.name, p) for p in rule.links):
            continue
        if rule.meshes and not _mesh_matches(shape, rule.meshes):
            continue
        return rule.policy, dict(rule.decompose) or params
    return default, params


def mesh_names(shape: Shape) -> list[str]:
    """The names a mesh pattern is matched against: id, file name, stem, URI as written."""
    geometry = shape.geometry
    if geometry.kind != "mesh":
        return []
    names = [geometry.mesh_id or "", geometry.uri or ""]
    if geometry.path:
        names += [PurePath(geometry.path).name, PurePath(geometry.path).stem]
    return [n for n in names if n]


def robot_mesh_names(robot: Robot) -> list[str]:
    """Every name a mesh pattern can match in ``robot`` (:func:`mesh_names` of each shape)."""
    return sorted(
        {name for link in robot.links for shape in link.shapes for name in mesh_names(shape)}
    )


def robot_mesh_ids(robot: Robot) -> list[str]:
    """The mjcfbuild names of ``robot``'s meshes, for a message's list of them."""
    return sorted(
        {
            shape.geometry.mesh_id
            for link in robot.links
            for shape in link.shapes
            if shape.geometry.kind == "mesh" and shape.geometry.mesh_id
        }
    )


def _mesh_matches(shape: Shape, patterns: tuple[str, ...]) -> bool:
    return any(fnmatch.fnmatchcase(name, p) for name in mesh_names(shape) for p in patterns)


def mesh_roles(robot: Robot, choices: list[CollisionChoice]) -> dict[str, list[str]]:
    """What each mesh file is needed for: drawing, colliding, its hull."""
    roles: dict[str, set[str]] = {}
    shapes = {(link.name, s.role, s.index): s for link in robot.links for s in link.shapes}
    for link in robot.links:
        for shape in link.visuals:
            if shape.geometry.kind == "mesh":
                assert shape.geometry.mesh_id is not None, "resolve gives every mesh an id"
                roles.setdefault(shape.geometry.mesh_id, set()).add("visual")
    for choice in choices:
        shape = shapes[(choice.link, choice.role, choice.index)]
        if shape.geometry.kind != "mesh":
            continue
        needed = collision_policy(choice.policy).mesh_role
        assert needed is not None, "a policy without a mesh role makes no choice"
        assert shape.geometry.mesh_id is not None, "resolve gives every mesh an id"
        roles.setdefault(shape.geometry.mesh_id, set()).add(needed)
    return {mesh_id: sorted(r) for mesh_id, r in sorted(roles.items())}


def decompositions(robot: Robot, choices: list[CollisionChoice]) -> dict[str, tuple[str, dict]]:
    """The decompositions to compute, by name: (mesh id, CoACD parameters).

    A decomposition is named after its mesh; a mesh decomposed with several parameter sets
    gets a suffix per set, so changing a threshold reruns the same task, not a new one.
    """
    shapes = {(link.name, s.role, s.index): s for link in robot.links for s in link.shapes}
    wanted: dict[str, dict[str, dict]] = {}
    for choice in choices:
        shape = shapes[(choice.link, choice.role, choice.index)]
        if collision_policy(choice.policy).coacd and shape.geometry.kind == "mesh":
            params = choice.decompose_params
            key = json.dumps(params, sort_keys=True)
            assert shape.geometry.mesh_id is not None, "resolve gives every mesh an id"
            wanted.setdefault(shape.geometry.mesh_id, {})[key] = params
    result = {}
    for mesh_id, sets in wanted.items():
        for params in sets.values():
            name = mesh_id if len(sets) == 1 else decompose_id(mesh_id, params)
            result[name] = (mesh_id, params)
    return dict(sorted(result.items()))


class _PatternRule(Protocol):
    """A robot.yaml collision rule, as far as matching goes."""

    @property
    def links(self) -> list[str]: ...

    @property
    def meshes(self) -> list[str]: ...


def check_rules(robot: Robot, rules: Sequence[_PatternRule], manifest_label: str) -> None:
    """Refuse a robot.yaml collision rule whose link patterns match no link of ``robot``, or
    whose mesh patterns match no mesh of it: always a typo, and the rule would change no
    geometry without a word (an actuator rule or a home joint that names nothing is refused
    the same way)."""
    from mjcfbuild.errors import ManifestError
    from mjcfbuild.sources.packages import listing, suggestion

    links = [link.name for link in robot.links]
    meshes = robot_mesh_names(robot)
    for index, rule in enumerate(rules):
        for key, noun, names in (("links", "link", links), ("meshes", "mesh", meshes)):
            patterns = list(getattr(rule, key))
            if not patterns or any(fnmatch.fnmatchcase(n, p) for n in names for p in patterns):
                continue
            raise ManifestError(
                f"rule matches no {noun} of the robot ({', '.join(patterns)})"
                f"{suggestion(patterns, names)}",
                file=f"{manifest_label} collision.rules[{index}].{key}",
                hint=f"its {key}: {listing(names)}",
            )
