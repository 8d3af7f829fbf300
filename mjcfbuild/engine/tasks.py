"""The build graph as doit task dictionaries, made by the task families in registry order.

The graph is built in two stages, the way ninja regenerates its manifest before building:

1. :func:`planning_tasks` - ``expand`` (xacro or URDF to URDF text), the ``attach:`` parts and
   ``plan`` (parse it, resolve every file, list the meshes). Their result says which mesh
   tasks exist.
2. :func:`build_tasks` - the planning tasks again (now up to date), then every build family's
   tasks (one ``mesh:<id>`` task per mesh file, ``assemble``, ``scene``, ...), made from the
   plan.

Each family (:mod:`mjcfbuild.families.registry`) declares its own tasks; this module only
gathers what they read from the plan into a :class:`~mjcfbuild.graph.graph.Graph` and asks
each in turn. The same generators serve the command line (through
:mod:`mjcfbuild.engine.loader`) and a user's own ``dodo.py`` (see the project's ``dodo.py``),
optionally with a name prefix.
"""

from __future__ import annotations

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.families.mjcfpart import mjcf_parts
from mjcfbuild.families.registry import build_families, planning_families
from mjcfbuild.graph.graph import Graph


def planning_tasks(ctx: BuildContext, prefix: str = "") -> list[dict]:
    """The tasks that decide what else gets built."""
    graph = Graph(ctx, prefix, mjcf_parts)
    return [task for family in planning_families() for task in family.tasks(graph)]


def build_tasks(ctx: BuildContext, prefix: str = "", with_planning: bool = True) -> list[dict]:
    """Every task of the build; reads the plan the planning tasks wrote."""
    graph = Graph(ctx, prefix, mjcf_parts)
    # What the plan says, read before any task is made: a bad plan or part fails first.
    for fact in ("plan", "robot", "parts", "choices", "roles", "decomposed"):
        getattr(graph, fact)
    tasks = planning_tasks(ctx, prefix) if with_planning else []
    families = build_families()
    for family in families:
        if family.verify is not None:
            family.verify(graph)
    return tasks + [task for family in families for task in family.tasks(graph)]
