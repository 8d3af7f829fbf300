"""The ``reference`` family: the check's independent reading of the URDF's kinematics."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mjcfbuild.graph.family import Family, file_task
from mjcfbuild.outputs import REFERENCE, planned_urdf
from mjcfbuild.steps.payloads import ReferencePayload
from mjcfbuild.steps.versions import REFERENCE as REFERENCE_STEP

if TYPE_CHECKING:
    from mjcfbuild.graph.graph import Graph


def _tasks(graph: Graph) -> list[dict]:
    """Reruns only when the URDF's kinematics change (check.reference.kinematic_digest), not
    for a damping or inertia edit; listed first, since it needs only the URDF and runs beside
    the meshes instead of after them."""
    if not graph.checks:
        return []
    from mjcfbuild.check.reference import kinematic_digest

    ctx = graph.ctx
    urdf = planned_urdf(ctx)
    payload = ReferencePayload(
        urdf=str(urdf),
        kinematics=kinematic_digest(urdf.read_bytes()),
        cache=ctx.cache_settings(),
        output=str(ctx.state(REFERENCE)),
    )
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}reference",
        "reference kinematics",
        payload,
        in_worker=True,
        file_dep=[],
        targets=[ctx.state(REFERENCE)],
    )
    return [task]


FAMILY = Family(
    name="reference",
    step="mjcfbuild.steps.reference:run",
    payload=ReferencePayload,
    format=REFERENCE_STEP.format,  # declared beside the step, which keys its products by it
    tools=REFERENCE_STEP.tools,
    tasks=_tasks,
)
