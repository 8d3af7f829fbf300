"""The ``assemble`` family: the model, assembled with MjSpec from the plan, the mesh products,
the decompositions, the matrix and the MJCF parts; and the settings it reads refused, before
anything is built, where they name no joint or link."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import ManifestError, MjcfbuildError
from mjcfbuild.families.decompose import decomposition_files
from mjcfbuild.families.mjcfpart import part_robot
from mjcfbuild.families.selfcollision import self_collision_matrix
from mjcfbuild.families.srdf import srdf_home_state, srdf_summary
from mjcfbuild.graph.family import Family, file_task, read_record
from mjcfbuild.outputs import (
    ASSEMBLY_REPORT,
    FLOOR_RECORD,
    MODEL_HEADER,
    PLAN,
    product_summary,
)
from mjcfbuild.sources.packages import did_you_mean
from mjcfbuild.steps.payloads import AssemblePayload

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph
    from mjcfbuild.manifest.models import InertiaSettings
    from mjcfbuild.urdf.model import Robot


def _inertia(inertia: InertiaSettings) -> dict:
    """robot.yaml's ``inertia:`` as the step's ``InertiaPolicy``; ``missing`` and ``density``
    only where masses come from geometry, so a robot built without them is up to date."""
    policy: dict = {
        "mode": inertia.policy,
        "min_mass": inertia.min_mass,
        "min_inertia": inertia.min_inertia,
    }
    if inertia.missing != "placeholder":
        policy.update(missing=inertia.missing, density=inertia.density)
    return policy


def _tasks(graph: Graph) -> list[dict]:
    ctx = graph.ctx
    meshes = sorted(graph.roles)
    options = ctx.manifest.options
    inertia = ctx.manifest.inertia
    source_label = ctx.portable_label(ctx.source_path)
    decompositions = decomposition_files(ctx, graph.decomposed)
    matrix = self_collision_matrix(graph)
    srdf = srdf_summary(graph)
    plan, parts = graph.plan, graph.parts
    payload = AssemblePayload(
        choices=[choice.to_dict() for choice in graph.choices],
        decompositions=decompositions,
        inputs={
            "urdf": plan.inputs.urdf,
            "file": plan.inputs.file,
            "native": ctx.manifest.mujoco_inputs.model_dump(mode="json"),
        },
        actuators=ctx.manifest.actuators.model_dump(mode="json"),
        motors=_motors(ctx),
        home=dict(ctx.manifest.home),
        floor=ctx.manifest.placement.floor,
        srdf_home=srdf_home_state(ctx),
        fuse_static=options.fuse_static,
        free_joint=options.free_joint,
        link_sites=options.link_sites,
        max_hull_vertices=ctx.manifest.meshes.max_hull_vertices,
        inertia=_inertia(inertia),
        header=f"{MODEL_HEADER} {source_label}; edit the sources, not this file.",
        assets_dir=str(ctx.assets_dir),
        self_collision=str(matrix) if matrix else None,
        srdf=str(srdf) if srdf else None,
        plan=str(ctx.state(PLAN)),
        products={mesh_id: str(product_summary(ctx, mesh_id)) for mesh_id in meshes},
        product_dirs={mesh_id: str(ctx.products_dir / mesh_id) for mesh_id in meshes},
        manifest_label=ctx.manifest_output_label,
        report=str(ctx.state(ASSEMBLY_REPORT)),
        floor_record=str(ctx.state(FLOOR_RECORD)),
        output=str(ctx.robot_path),
        mjcf_parts=parts,
        forcerange_at=_forcerange_at(ctx),
    )
    task = file_task(
        ctx,
        FAMILY,
        f"{graph.prefix}assemble",
        f"assemble {ctx.manifest.robot_file}",
        payload,
        in_worker=True,
        file_dep=[
            ctx.state(PLAN),
            *(product_summary(ctx, m) for m in meshes),
            *(Path(d.summary) for d in decompositions),
            *([matrix] if matrix else []),
            *([srdf] if srdf else []),
            *(Path(path) for part in parts for path in (part.xml, part.summary)),
            # motor files: their values are in the payload; listed so the no-op path sees edits
            *(ctx.resolve(name) for name in ctx.manifest.motors.files),
        ],
        targets=[ctx.robot_path, ctx.state(ASSEMBLY_REPORT), ctx.state(FLOOR_RECORD)],
    )
    return [task]


def _forcerange_at(ctx: GraphContext) -> list[str]:
    """Where robot.yaml writes each actuators rule's forcerange, as a warning names it
    (``robot.yaml:5: actuators.rules[0].forcerange``); "" for a rule without one, so that only
    the lines of forceranges count in the task's parameters."""
    from mjcfbuild.manifest.pinpoint import key_line

    found = []
    for index, rule in enumerate(ctx.manifest.actuators.rules):
        if rule.forcerange is None:
            found.append("")
            continue
        setting = f"actuators.rules[{index}].forcerange"
        line = key_line(ctx.manifest_file, setting)
        label = ctx.manifest_output_label
        found.append(f"{label}:{line}: {setting}" if line else f"{label} {setting}")
    return found


def _verify(graph: Graph) -> None:
    """Refuse actuator rules and home values that name no joint, and collision rules and
    decompose_mesh inputs that match no link or mesh, before anything is built."""
    from mjcfbuild.collision.policy import check_rules as check_collision_rules
    from mjcfbuild.control.choose import check_rules
    from mjcfbuild.control.home import home_values
    from mjcfbuild.manifest.collision_settings import check_decompose_inputs
    from mjcfbuild.manifest.pinpoint import pinpoint

    ctx = graph.ctx
    robot = part_robot(ctx, graph.robot, graph.parts)
    try:
        check_rules(robot, ctx.manifest.actuators, ctx.manifest_label)
        check_collision_rules(graph.robot, ctx.manifest.collision.rules, ctx.manifest_label)
        check_decompose_inputs(ctx.manifest, graph.plan.inputs, graph.robot, ctx.manifest_label)
        _motors(ctx)  # an unknown motor or a bad motor file, before anything is built
        home_values(robot, graph.plan.control(), ctx.manifest.home, None, ctx.manifest_label)
        _check_kept_pairs(robot, ctx)
        _check_floor_contacts(robot, ctx)
    except MjcfbuildError as error:
        if ctx.manifest_file is not None:
            pinpoint(error, ctx.manifest_label, ctx.manifest_file)
        raise


def _motors(ctx: GraphContext) -> dict[str, dict]:
    """The motors the actuator rules name (control.catalogue), their datasheet values."""
    from mjcfbuild.control.catalogue import resolve_motors

    return resolve_motors(
        ctx.manifest.motors,
        ctx.manifest.actuators.rules,
        ctx.base_dir,
        ctx.manifest_label,
    )


def _check_kept_pairs(robot: Robot, ctx: GraphContext) -> None:
    settings = ctx.manifest.self_collision
    if settings == "none":
        return
    for index, pair in enumerate(settings.keep):
        for link in pair:
            _refuse_unknown_link(robot, link, f"self_collision.keep[{index}]", ctx)


def _check_floor_contacts(robot: Robot, ctx: GraphContext) -> None:
    settings = ctx.manifest.training
    if settings is None:
        return
    for key in ("add", "remove"):
        for index, link in enumerate(getattr(settings.floor_contacts, key)):
            where = f"output.training.floor_contacts.{key}[{index}]"
            _refuse_unknown_link(robot, link, where, ctx)


def _refuse_unknown_link(robot: Robot, link: str, key: str, ctx: GraphContext) -> None:
    """:class:`ManifestError` unless ``link``, given at manifest ``key``, is a robot link."""
    from mjcfbuild.sources.packages import listing

    links = [each.name for each in robot.links]
    if link not in links:
        raise ManifestError(
            f"link '{link}' is not a link of the robot{did_you_mean(link, links)}",
            file=f"{ctx.manifest_label} {key}",
            hint=f"links: {listing(links)}",
        )


def _report(ctx: GraphContext) -> dict:
    """The model's size, files, repairs, readiness to control and collision matrix."""
    assembly = read_record(ctx.state(ASSEMBLY_REPORT))
    report = {
        "repairs": assembly.get("repairs", []),
        "bodies": assembly.get("bodies"),
        "geoms": assembly.get("geoms"),
        "assets": assembly.get("assets", []),
        "readiness": assembly.get("readiness") or {},
        "self_collision": assembly.get("self_collision"),
    }
    if assembly.get("geometry_masses"):  # robot.yaml's inertia.missing: geometry
        report["geometry_masses"] = assembly["geometry_masses"]
    return report


FAMILY = Family(
    name="assemble",
    step="mjcfbuild.steps.assemble:run",
    payload=AssemblePayload,
    # 12: the Gazebo sensors' MJCF counterparts; 13: the products' binary copies; 14: a raw
    # timestep a build cannot simulate with refused; 15: reversed ranges in the inputs refused;
    # 16: an inertia repair names the link's file and line; 17: an underactuated mechanism's
    # read-only joints' reductions are no gear ratios, one warning per mechanism; 18: curved
    # feet touch the floor at their lowest points (a stance on two spheres is a line); an
    # unused asset the user edited is kept; 19: a limit that is no limit is named at the
    # joint's file and line (placed in a xacro source); a URDF floating joint from `world`
    # floats the robot, stood on the floor; a joint whose inertia rounds away is refused; an
    # axis given at any length written as its unit axis at 12 digits; a user's tendon
    # actuator named in its record; 20: a URDF floating joint has no home value (the report
    # listed it at 0); 21: a warning where lidar rays are most of a step; 22: free_joint on a
    # URDF rooted at `world` floats what the world holds as one whole; an <intvelocity>'s
    # home is ctrl 0 and act at the pose; a root holding the robot by a floating joint is the
    # world body; a velocity servo's kv at least 49 times the joint's damping; 23: a floating
    # robot stood on the floor by its own geometry, not the world body's; 24: lidar rays counted
    # as mujoco_ros2_control and the reference converter count them; 25: modify and Gazebo
    # link lookups suggest a name, no reduction advice for a joint nothing drives; 26: COLLADA
    # emission and vertex colours in materials, geoms of a DAE without a scene left out, a flat
    # collision mesh under `primitive` a thin box; 27: the floor under the visual geometry of
    # a fixed robot with nothing colliding, placeholder-sized rotor inertias warned of
    format=27,
    tools=("mujoco", "numpy", "lxml"),
    tasks=_tasks,
    compiles_model=True,
    verify=_verify,
    report=_report,
)
