"""The ``plan`` family: the URDF parsed, every file it names resolved, the meshes listed; the
plan decides which mesh and decomposition tasks the build stage makes."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mjcfbuild.families.parts import part_folders
from mjcfbuild.graph.family import (
    Family,
    discovered_inputs,
    file_task,
    package_folders,
    require_file,
    ros_environment,
    ros_package_index,
)
from mjcfbuild.graph.uptodate import planned_meshes_exist
from mjcfbuild.outputs import PLAN, PLAN_DEPS, SOURCE_URDF, planned_urdf
from mjcfbuild.steps.payloads import PlanPayload

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


def _tasks(graph: Graph) -> list[dict]:
    ctx = graph.ctx
    urdf = planned_urdf(ctx)
    inputs_file = None
    if ctx.manifest.mujoco_inputs.file:
        inputs_file = ctx.resolve(ctx.manifest.mujoco_inputs.file)
        require_file(ctx, inputs_file, "inputs file", "mujoco_inputs.file")
    expanded = ctx.source_kind == "xacro" or urdf != ctx.state(SOURCE_URDF)
    prebuilt = ctx.prebuilt_mesh_dir  # convert -a
    payload = PlanPayload(
        urdf=str(urdf),
        display=ctx.label(urdf if expanded else ctx.source_path),
        expanded_from=ctx.label(ctx.source_path) if expanded else None,
        base_dir=str(ctx.source_base_dir),
        packages=package_folders(ctx.resolver.explicit),
        environment=ros_environment(ctx),
        package_index=ros_package_index(ctx),
        inputs_file=str(inputs_file) if inputs_file else None,
        inputs_file_label=ctx.label(inputs_file) if inputs_file else None,
        output=str(ctx.state(PLAN)),
        prebuilt_meshes=str(prebuilt) if prebuilt is not None else None,
        roots=None if ctx.manifest.source.read_outside else _description_roots(ctx),
        depfile=str(ctx.state(PLAN_DEPS)),
    )
    # A rerun where a texture it did not find appeared, or one it found was removed; what a
    # found texture holds does not matter to the plan (so it is no file dependency).
    _, stale = discovered_inputs(ctx, ctx.state(PLAN_DEPS))
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}plan",
        "plan",
        payload,
        in_worker=False,
        file_dep=[urdf, *([inputs_file] if inputs_file else [])],
        targets=[ctx.state(PLAN)],
        extra_uptodate=[planned_meshes_exist(ctx.state(PLAN)), *stale],
    )
    return [task]


def _description_roots(ctx: GraphContext) -> list[str]:
    """The folders a description reads from without a warning: robot.yaml's, the source
    file's, the packages robot.yaml names, and those of the parts it attaches."""
    folders = [ctx.base_dir, ctx.source_base_dir, *ctx.resolver.explicit.values()]
    return sorted({str(ctx.resolve(str(folder))) for folder in [*folders, *part_folders(ctx)]})


FAMILY = Family(
    name="plan",
    step="mjcfbuild.steps.plan:run",
    payload=PlanPayload,
    # 5: ros2_control <hardware>; 6: chains deeper than MuJoCo reads; 7: Gazebo sensors;
    # 8: processed inputs by tag; 9: a mimic of a fixed joint, or a ring of mimics, refused;
    # 10: a revolute or prismatic joint without <limit> warned of; names twice say where first;
    # 12: each transmission's actuators and type (underactuated mechanisms); 13: a URDF's
    # <compiler inertiafromgeom> said not to be applied; <hardware> params and which
    # transmissions are ros2_control's; 14: the hardware plugin of each of those; 15: each
    # joint's and sensor's block plugin, a joint's mimic param, <hardware> params of the
    # blocks mujoco_ros2_control runs only; a floating joint below the root refused at its line;
    # 16: whether each ros2_control joint has a position state interface; 17: its block and
    # mimic attribute; 18: each geometry's own line; 19: a ROS 1 transmission naming a joint the
    # URDF lacks warned of, joint types suggested; 20: each mesh's looks_from (convert -a), each
    # transmission's block, joint reduction, offset and roleless elements, <hardware> param
    # lines; a closing tag after the root read with a warning; 21: a second root element and
    # Latin-1 bytes read as MuJoCo reads them, a late <?...?> warned of; each ros2_control
    # block's unknown children and joint-less transmissions, each joint's state interfaces;
    # each material's texture line, a missing texture warned of (None), not refused
    format=21,
    tools=("lxml",),
    tasks=_tasks,
    stage="planning",
)
