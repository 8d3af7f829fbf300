"""The build graph as doit task dictionaries, made by the task families in registry order.

The graph is built in two stages, the way ninja regenerates its manifest before building:

1. :func:`planning_tasks` - ``expand`` (xacro or URDF to URDF text), the ``attach:`` parts and
   ``plan`` (parse it, resolve every file, list the meshes). Their result says which mesh
   tasks exist.
2. :func:`build_tasks` - the planning tasks again (now up to date), then every build family's
   tasks (one ``mesh:<id>`` task per mesh file, ``assemble``, ``scene``, ...), made from the
   plan.

Each family (:mod:`mjcfbuild.families.registry`) declares its own tasks; this module only
gathers what they read from the plan into a :class:`Graph` and asks each in turn. The same
generators serve the command line (through :mod:`mjcfbuild.engine.loader`) and a user's own
``dodo.py`` (see the project's ``dodo.py``), optionally with a name prefix.
"""

from __future__ import annotations

from functools import cached_property
from typing import TYPE_CHECKING

from mjcfbuild.compose.tasks import mjcf_parts
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.families.registry import build_families, planning_families
from mjcfbuild.outputs import PLAN
from mjcfbuild.steps.payloads import MjcfPartFiles
from mjcfbuild.steps.plan_record import Plan, read_plan

if TYPE_CHECKING:
    from mjcfbuild.collision.policy import CollisionChoice
    from mjcfbuild.urdf.model import Robot


class Graph:
    """What the families make their tasks from: the build's context and the task name prefix,
    and, read once when a build family first asks, what the plan says."""

    def __init__(self, ctx: BuildContext, prefix: str = "") -> None:
        self.ctx = ctx
        self.prefix = prefix

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
        return mjcf_parts(self.ctx, self.robot)

    @cached_property
    def choices(self) -> list[CollisionChoice]:
        """Each link's collision choice."""
        from mjcfbuild.collision.settings import collision_settings

        return collision_settings(self.ctx.manifest, self.plan.inputs).choose(self.robot)

    @cached_property
    def roles(self) -> dict[str, list[str]]:
        """Mesh id -> what its product is used for (visual, collision, hull)."""
        from mjcfbuild.collision.policy import mesh_roles

        return mesh_roles(self.robot, self.choices)

    @cached_property
    def paths(self) -> dict[str, str]:
        """Mesh id -> its file."""
        return {mesh.id: mesh.path for mesh in self.plan.meshes}

    @cached_property
    def decomposed(self) -> dict[str, tuple[str, dict]]:
        """Decomposition name -> the mesh it decomposes and its parameters."""
        from mjcfbuild.collision.policy import decompositions

        return decompositions(self.robot, self.choices)


def planning_tasks(ctx: BuildContext, prefix: str = "") -> list[dict]:
    """The tasks that decide what else gets built."""
    graph = Graph(ctx, prefix)
    return [task for family in planning_families() for task in family.tasks(graph)]


def build_tasks(ctx: BuildContext, prefix: str = "", with_planning: bool = True) -> list[dict]:
    """Every task of the build; reads the plan the planning tasks wrote."""
    graph = Graph(ctx, prefix)
    # What the plan says, read before any task is made: a bad plan or part fails first.
    for fact in ("plan", "robot", "parts", "choices", "roles", "decomposed"):
        getattr(graph, fact)
    tasks = planning_tasks(ctx, prefix) if with_planning else []
    families = build_families()
    for family in families:
        if family.verify is not None:
            family.verify(graph)
    return tasks + [task for family in families for task in family.tasks(graph)]
