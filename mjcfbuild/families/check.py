"""The ``check`` family: the model against the URDF and each MJCF part alone, and ready to
control (``check.enabled``)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.graph.family import (
    Family,
    discovered_inputs,
    file_task,
    package_folders,
    read_record,
)
from mjcfbuild.outputs import ASSEMBLY_REPORT, CHECK_DEPS, CHECK_RESULTS, PLAN, REFERENCE
from mjcfbuild.steps.payloads import CheckPayload, MjcfPartFiles

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


def check_payload(
    ctx: GraphContext, parts: list[MjcfPartFiles], options: dict | None = None
) -> CheckPayload:
    """What the check is given: the build's ``check`` task and ``mjcfbuild check`` alike
    (``options``, CheckOptions' fields, replace the manifest's check settings)."""
    settings = ctx.manifest.check
    return CheckPayload(
        options=options
        or {
            "configurations": settings.configurations,
            "position_tolerance": settings.position_tolerance,
            "rotation_tolerance": settings.rotation_tolerance,
            "steps": settings.steps,
            "hold_tolerance": settings.hold_tolerance,
            "seed": 0,
        },
        plan=str(ctx.state(PLAN)),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        model=str(ctx.robot_path),
        model_label=ctx.label(ctx.robot_path),
        scene=str(ctx.scene_path),
        reference=str(ctx.state(REFERENCE)),
        output=str(ctx.state(CHECK_RESULTS)),
        mjcf_parts=parts,  # each compared with the part compiled alone
        depfile=str(ctx.state(CHECK_DEPS)),
        packages=package_folders(ctx.resolver.explicit),
    )


def _tasks(graph: Graph) -> list[dict]:
    if not graph.checks:
        return []
    ctx, parts = graph.ctx, graph.parts
    read, stale = discovered_inputs(ctx, ctx.state(CHECK_DEPS))
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}check",
        f"check {ctx.manifest.robot_file}",
        check_payload(ctx, parts),
        in_worker=True,
        file_dep=[
            ctx.robot_path,
            ctx.scene_path,
            ctx.state(PLAN),
            ctx.state(ASSEMBLY_REPORT),
            ctx.state(REFERENCE),
            *(Path(path) for part in parts for path in (part.xml, part.summary)),
            *read,
        ],
        targets=[ctx.state(CHECK_RESULTS)],
        extra_uptodate=stale,
    )
    return [task]


def _report(ctx: GraphContext) -> dict:
    """The check's results for the report: none where a build without the check (--no-check)
    changed the model or scene since they were found, which would be another model's."""
    results = ctx.state(CHECK_RESULTS)
    if not ctx.run_check and results.exists() and _older(results, ctx.robot_path, ctx.scene_path):
        return {"check": {}, "check_not_run": "--no-check"}
    return {"check": read_record(results)}


def _older(path: Path, *than: Path) -> bool:
    """Whether ``path`` was last written before any of ``than`` (those that exist)."""
    written = path.stat().st_mtime_ns
    return any(other.exists() and other.stat().st_mtime_ns > written for other in than)


FAMILY = Family(
    name="check",
    step="mjcfbuild.steps.check:run",
    payload=CheckPayload,
    format=26,  # 9: the Gazebo sensors table; torque-motor and wheel stand verdicts; 10: speeds
    # measured again from inside the joint ranges, velocity limits of 1e6 and above taken for
    # none, unstable-state warnings naming their joint; 11: a hold failure of a servo whose
    # keyframe ctrl is not its position says so; 12: check.json holds the console's verdict and
    # which checks failed (the report's verdict names checks that did not run); 13: joints
    # without an actuator that sag from home, curved feet's stance, warnings in the verdict;
    # 14: a free body compared where the URDF places it (a floating joint's origin), a
    # prismatic joint's travel along its unit axis; the runtime's start-up rules for tendon
    # actuators, initial_keyframe and ros2_control transmissions; a part's unnamed joint
    # found by the name the build gave it; a user's servo not said to lack a URDF effort;
    # 15: transmissions of a block for another hardware plugin warned of, not failed; 16: the
    # runtime's 2026 rules: PID gains read from the pids_config_file, position or velocity
    # without them a failure, joints the URDF lacks, mimic joints, other plugins' blocks,
    # <intvelocity>, odometry's free joint, effort at start; a density just past its bound
    # shown with the digits that tell it from the bound; 17: a runtime start away from home
    # (no initial_keyframe) said; 18: the floor gap of a floating robot's own geometry; 19: the
    # runtime's lidar ray count, cameras without a resolution; 20: ros2_control's parser
    # refusals (fixed and mimic joints) and register_transmissions' (2026); 21: a floating
    # robot whose passive joints give way needs a controller, not stiffer servos; 22: the
    # report's table has every check the console shows; 23: weak servos beside a passive joint
    # fail the stand; other plugins' transmissions named one by one; 24: a massless marker
    # link's geometry making a body look too light is warned about, not failed; 25: the
    # runtime's transmission, mujoco_model, unsupported-actuator and unnamed-joint rules; 26:
    # the parser's unknown block children, joint-less and unknown-type transmissions, site
    # actuators in transmissions, interface-less joints, a keyframe start through a reduction
    tools=("mujoco", "numpy"),
    tasks=_tasks,
    compiles_model=True,
    report_only=True,
    report=_report,
)
