"""Which geometry each link collides with, chosen by name patterns in robot.yaml.

Every visual and every authored collision of a link is a *candidate*. Each candidate gets the
policy of the first rule that matches it (by link name and/or mesh name), or the default:

* ``authored`` - keep the URDF's own ``<collision>`` shapes (candidates that are collisions);
* ``visual`` - collide with the visual shapes, as the mujoco_ros2_control converter did;
* ``hull`` / ``decompose`` / ``primitive`` - take the link's *source* shapes (its collisions if
  it has any, otherwise its visuals) and use, for each mesh, its convex hull, its CoACD convex
  decomposition, or the best-fitting box, capsule, cylinder or sphere; primitives stay as they
  are;
* ``none`` - no collision geometry.
"""

from __future__ import annotations

import fnmatch
import hashlib
import json
from dataclasses import dataclass
from pathlib import PurePath

from mjcfbuild.urdf.model import Link, Robot, Shape

POLICIES = ("authored", "visual", "hull", "decompose", "primitive", "none")
TRANSFORMING = ("hull", "decompose", "primitive")


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
            policy=rule["policy"],
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
            policy, params = _policy_for(link, shape, default, rules, default_decompose)
            emit = (
                (policy == "authored" and shape.role == "collision")
                or (policy == "visual" and shape.role == "visual")
                or (policy in TRANSFORMING and shape.role == source_role)
            )
            if emit:
                decompose = tuple(sorted(params.items())) if policy == "decompose" else ()
                choices.append(
                    CollisionChoice(link.name, shape.role, shape.index, policy, decompose)
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
        needed = {
            "authored": "collision",
            "visual": "collision",
            "decompose": "collision",
            "hull": "hull",
            "primitive": "hull",
        }[choice.policy]
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
        if choice.policy == "decompose" and shape.geometry.kind == "mesh":
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
