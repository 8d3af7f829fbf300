"""Every task family of a build, in the order their tasks are listed in the graph (doit starts
ready tasks in that order), and the tables the engine derives from them.

Adding a family: write its module (a :class:`~mjcfbuild.graph.family.Family` named
``FAMILY``), its step in :mod:`mjcfbuild.steps`, and list it here (docs/architecture.md).
"""

from __future__ import annotations

from mjcfbuild.families import (
    assemble,
    check,
    compose,
    decompose,
    expand,
    export_urdf,
    mesh,
    mjcfpart,
    package,
    page,
    plan,
    previews,
    reference,
    scene,
    selfcollision,
    srdf,
    training,
    tuning,
)
from mjcfbuild.graph.family import Family

FAMILIES: tuple[Family, ...] = (
    # planning: what they write decides which build tasks exist
    expand.FAMILY,
    mjcfpart.FAMILY,
    compose.FAMILY,
    plan.FAMILY,
    # build; the reference first: it needs only the URDF, and runs beside the meshes
    reference.FAMILY,
    mesh.FAMILY,
    decompose.FAMILY,
    srdf.FAMILY,
    selfcollision.FAMILY,
    assemble.FAMILY,
    scene.FAMILY,
    export_urdf.FAMILY,
    training.FAMILY,
    check.FAMILY,
    previews.FAMILY,
    tuning.FAMILY,
    package.FAMILY,
    page.FAMILY,
)
BY_NAME = {family.name: family for family in FAMILIES}

# Bump a family's format (in its module) when its output for the same inputs changes.
STEP_FORMATS = {family.name: family.format for family in FAMILIES}
STEP_TOOLS = {family.name: family.tools for family in FAMILIES}
# The steps that compile the built model with MuJoCo (engine.session sends each where one ran).
COMPILES_MODEL = frozenset(family.step for family in FAMILIES if family.compiles_model)
# The tasks whose output is the report's only: freshness does not count them.
REPORT_TASKS = tuple(family.name for family in FAMILIES if family.report_only)
# The tasks a build makes only for the check: the report's, and the reference reading of the
# URDF the check compares the model with (a build without the check makes none of them).
CHECK_ONLY_TASKS = (*REPORT_TASKS, reference.FAMILY.name)
# Their modules, which a build that checks preloads in its workers.
CHECK_MODULES = tuple(family.module for family in FAMILIES if family.report_only)


def step_versions(step: str) -> dict[str, str]:
    """What family ``step``'s output depends on besides its inputs: tool versions and its
    format."""
    return BY_NAME[step].versions()


def planning_families() -> list[Family]:
    """The families whose tasks are made before the plan exists."""
    return [family for family in FAMILIES if family.stage == "planning"]


def build_families() -> list[Family]:
    """The families whose tasks are made from the plan."""
    return [family for family in FAMILIES if family.stage == "build"]
