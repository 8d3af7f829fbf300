"""The collision settings of one build, in the plain form tasks and steps share.

robot.yaml's ``collision:`` rules come first; ``decompose_mesh`` inputs (from the URDF, the
inputs file or robot.yaml's ``mujoco_inputs``) become rules after them, each decomposing one
mesh with its own threshold and the default CoACD parameters. ``meshes.max_hull_vertices``
caps the vertices of CoACD's parts too.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from mjcfbuild.collision.policy import CollisionChoice
    from mjcfbuild.inputs.processed import DecomposeInput
    from mjcfbuild.manifest.models import Manifest
    from mjcfbuild.urdf.model import Robot


class FoundInputs(Protocol):
    """The MuJoCo inputs a plan found (steps.plan_record.PlannedInputs): those of the URDF and
    of the inputs file, by ``where``. Collision sits below the steps, so it names only this."""

    def get(self, where: str) -> dict[str, Any] | None: ...


@dataclass(frozen=True)
class EffectiveCollisionSettings:
    """robot.yaml's ``collision:`` with the plan's ``decompose_mesh`` inputs added: the default
    policy, the rules (first match wins) and the default CoACD parameters."""

    default: str
    rules: list[dict[str, Any]]
    decompose: dict[str, Any]

    def choose(self, robot: Robot) -> list[CollisionChoice]:
        """The collision geometry of every link of ``robot`` under these settings."""
        from mjcfbuild.collision.policy import choose_collisions, rules_from_dicts

        return choose_collisions(robot, self.default, rules_from_dicts(self.rules), self.decompose)


def collision_settings(manifest: Manifest, plan_inputs: FoundInputs) -> EffectiveCollisionSettings:
    """The collision settings of ``manifest`` with the ``decompose_mesh`` inputs of the plan."""
    settings = manifest.collision
    defaults = dict(settings.decompose_defaults)
    limit = manifest.meshes.max_hull_vertices
    thresholds: dict[str, float] = {}
    for item in _decompose_inputs(manifest, plan_inputs):
        thresholds[item.mesh] = item.threshold
    rules = [dict(rule, decompose=dict(rule["decompose"])) for rule in settings.effective_rules] + [
        {
            "links": [],
            "meshes": [mesh],
            "policy": "decompose",
            "decompose": {**defaults, "threshold": threshold},
        }
        for mesh, threshold in sorted(thresholds.items())
    ]
    if limit is not None:
        for params in [defaults, *(rule["decompose"] for rule in rules)]:
            if params:
                params["max_ch_vertex"] = min(int(params["max_ch_vertex"]), limit)
    return EffectiveCollisionSettings(settings.default, rules, defaults)


def check_decompose_inputs(
    manifest: Manifest, plan_inputs: FoundInputs, robot: Robot, manifest_label: str
) -> None:
    """Refuse, at its line, a ``decompose_mesh`` input (URDF, inputs file or robot.yaml) that
    names no mesh of ``robot``: its rule would decompose nothing without a word, as a
    ``collision.rules[].meshes`` pattern that matches nothing would (``check_rules``)."""
    import fnmatch

    from mjcfbuild.collision.policy import robot_mesh_ids, robot_mesh_names
    from mjcfbuild.errors import InputError
    from mjcfbuild.inputs.model import origin_location
    from mjcfbuild.sources.packages import listing, suggestion

    names = robot_mesh_names(robot)
    where = f"{manifest_label} mujoco_inputs.decompose"
    own = [
        item.given_at(f"{where}[{index}]")
        for index, item in enumerate(manifest.mujoco_inputs.decompose)
    ]
    for item in _found_decompose_inputs(plan_inputs) + own:
        if any(fnmatch.fnmatchcase(name, item.mesh) for name in names):
            continue
        file, line = origin_location(item.origin)
        raise InputError(
            f"decompose_mesh '{item.mesh}' names no mesh of the robot"
            f"{suggestion([item.mesh], names)}",
            file=file,
            line=line,
            hint=f"fix the name; mesh names: {listing(robot_mesh_ids(robot))}, or a mesh's "
            "file name, stem or URI",
        )


def _found_decompose_inputs(plan_inputs: FoundInputs) -> list[DecomposeInput]:
    """The ``decompose_mesh`` inputs of the URDF and the inputs file, in that order."""
    from mjcfbuild.inputs.model import inputs_from_dict
    from mjcfbuild.inputs.processed import DecomposeInput

    items: list[DecomposeInput] = []
    for source in ("urdf", "file"):
        data = plan_inputs.get(source)
        if data:
            items += inputs_from_dict(data).of(DecomposeInput)
    return items


def _decompose_inputs(manifest: Manifest, plan_inputs: FoundInputs) -> list[DecomposeInput]:
    """The ``decompose_mesh`` inputs of the URDF, the inputs file and robot.yaml, in that order."""
    return _found_decompose_inputs(plan_inputs) + list(manifest.mujoco_inputs.decompose)
