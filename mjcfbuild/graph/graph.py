"""What the task families make their tasks from: a :class:`Graph` of one build."""

from __future__ import annotations

from collections.abc import Callable
from functools import cached_property
from typing import TYPE_CHECKING

from mjcfbuild.graph.context import GraphContext
from mjcfbuild.outputs import PLAN
from mjcfbuild.steps.payloads import MjcfPartFiles
from mjcfbuild.steps.plan_record import Plan, read_plan

if TYPE_CHECKING:
    from mjcfbuild.collision.policy import CollisionChoice
    from mjcfbuild.urdf.model import Robot

# Reads and checks the ``attach:`` MJCF parts of a build (the mjcfpart family's records).
PartsReader = Callable[[GraphContext, "Robot"], list[MjcfPartFiles]]


class Graph:
    """What the families make their tasks from: the build's context and the task name prefix,
    and, read once when a build family first asks, what the plan says. ``read_parts`` is the
    ``attach:`` family's reader of its parts (the families sit above this package)."""

    def __init__(
        self, ctx: GraphContext, prefix: str = "", read_parts: PartsReader | None = None
    ) -> None:
        self.ctx = ctx
        self.prefix = prefix
        self._read_parts = read_parts

    @property
    def checks(self) -> bool:
        """Whether this build checks the model (the report's tasks are made)."""
        return self.ctx.manifest.check.enabled and self.ctx.run_check

    @cached_property
    def plan(self) -> Plan:
        """The plan the planning stage wrote."""
        return read_plan(self.ctx.state(PLAN))

    @cached_property
    def robot(self) -> Robot:
        """The robot the plan read."""
        return self.plan.robot_model()

    @cached_property
    def parts(self) -> list[MjcfPartFiles]:
        """The ``attach:`` MJCF parts, checked and in attach order."""
        assert self._read_parts is not None, "a build graph is given its parts' reader"
        return self._read_parts(self.ctx, self.robot)

    @cached_property
    def choices(self) -> list[CollisionChoice]:
        """Each link's collision choice."""
        from mjcfbuild.manifest.collision_settings import collision_settings

        return collision_settings(self.ctx.manifest, self.plan.inputs).choose(self.robot)

    @cached_property
    def roles(self) -> dict[str, list[str]]:
        """Mesh id -> what its product is used for (visual, collision, hull)."""
        from mjcfbuild.collision.policy import mesh_roles

        roles = mesh_roles(self.robot, self.choices)
        if self.ctx.manifest.inertia.missing == "geometry":
            from mjcfbuild.mjcf.geometry_mass import weighed_meshes

            # A link without a mass is weighed from its meshes' collision files.
            for mesh_id in weighed_meshes(self.robot):
                roles[mesh_id] = sorted({*roles.get(mesh_id, []), "collision"})
            roles = dict(sorted(roles.items()))
        return roles

    @cached_property
    def paths(self) -> dict[str, str]:
        """Mesh id -> its file."""
        return {mesh.id: mesh.path for mesh in self.plan.meshes}

    @cached_property
    def looks_from(self) -> dict[str, str]:
        """Mesh id -> the mesh file whose look its pre-generated OBJ takes (convert -a)."""
        return {mesh.id: mesh.looks_from for mesh in self.plan.meshes if mesh.looks_from}

    @cached_property
    def decomposed(self) -> dict[str, tuple[str, dict]]:
        """Decomposition name -> the mesh it decomposes and its parameters."""
        from mjcfbuild.collision.policy import decompositions

        return decompositions(self.robot, self.choices)
