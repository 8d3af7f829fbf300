"""The build graph as doit task dictionaries.

The graph is built in two stages, the way ninja regenerates its manifest before building:

1. :func:`planning_tasks` - ``expand`` (xacro or URDF to URDF text) and ``plan`` (parse it,
   resolve every file, list the meshes). Their result says which mesh tasks exist.
2. :func:`build_tasks` - the planning tasks again (now up to date), one ``mesh:<id>`` task per
   mesh file, ``assemble`` and ``scene``.

The same generators serve the command line (through :mod:`mjcfbuild.engine.loader`) and a
user's own ``dodo.py`` (see the project's ``dodo.py``), optionally with a name prefix.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from doit.exceptions import TaskFailed

from mjcfbuild.collision.policy import decompositions, mesh_roles
from mjcfbuild.collision.settings import collision_settings
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.render_inputs import RenderInputsUnchanged
from mjcfbuild.engine.uptodate import (
    ParamsUnchanged,
    always_stale,
    outputs_intact,
    planned_meshes_exist,
)
from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import unreadable_file
from mjcfbuild.sources.packages import ENV_VARIABLES, did_you_mean
from mjcfbuild.steps.depfile import Depfile
from mjcfbuild.steps.payloads import (
    AssemblePayload,
    CheckPayload,
    DecomposePayload,
    DecompositionFiles,
    ExpandPayload,
    ExportUrdfPayload,
    MeshOptions,
    MeshPayload,
    MjcfPartFiles,
    PackagePayload,
    PagePayload,
    Payload,
    PlanPayload,
    PreviewsPayload,
    ReferencePayload,
    ScenePayload,
    SelfCollisionPayload,
    SrdfPayload,
    TrainingPayload,
    TuningPayload,
)
from mjcfbuild.steps.plan_record import Plan, read_plan
from mjcfbuild.steps.versions import step_versions
from mjcfbuild.urdf.mesh_uses import mesh_uses

if TYPE_CHECKING:
    from mjcfbuild.collision.policy import CollisionChoice
    from mjcfbuild.urdf.model import Robot

SOURCE_URDF = "source.urdf"
SOURCE_DEPS = "source.deps.json"
COMPOSED_URDF = "composed.urdf"
PLAN = "plan.json"
ASSEMBLY_REPORT = "assembly.json"
# The lowest collision point at home, apart from the assembly report, so the scene's floor
# follows it without rerunning for every other change of the model.
FLOOR_RECORD = "floor.json"
URDF_EXPORT_RECORD = "urdf_export.json"
PREVIEWS_RECORD = "previews.json"
TUNING_RECORD = "tuning.json"
PACKAGE_RECORD = "package.json"
PACKAGE_FOLDER = "package"  # the Menagerie-grade folder, inside the output folder
# The report page's files, inside the report folder (mjcfbuild.steps.page writes them).
PAGE_FILES = (
    "index.html",
    "page/mujoco.js",
    "page/mujoco-wasm.js",
    "page/model.js",
    "page/viewer.js",
    "page/page.css",
)


def planning_tasks(ctx: BuildContext, prefix: str = "") -> list[dict]:
    """The tasks that decide what else gets built."""
    from mjcfbuild.engine.part_tasks import composition_tasks

    return [_expand_task(ctx, prefix), *composition_tasks(ctx, prefix), _plan_task(ctx, prefix)]


def build_tasks(ctx: BuildContext, prefix: str = "", with_planning: bool = True) -> list[dict]:
    """Every task of the build; reads the plan the planning tasks wrote."""
    from mjcfbuild.engine.part_tasks import mjcf_parts, part_robot

    plan = read_plan(ctx.state(PLAN))
    robot = plan.robot_model()
    parts = mjcf_parts(ctx, robot)  # attach: MJCF parts, checked and in attach order
    collision = collision_settings(ctx.manifest, plan.inputs)
    choices = collision.choose(robot)
    roles = mesh_roles(robot, choices)
    paths = {mesh.id: mesh.path for mesh in plan.meshes}
    decomposed = decompositions(robot, choices)
    tasks = planning_tasks(ctx, prefix) if with_planning else []
    checks = ctx.manifest.check.enabled and ctx.run_check
    if checks:  # first: it needs only the URDF, and runs beside the meshes instead of after them
        tasks.append(_reference_task(ctx, prefix))
    tasks += [
        _mesh_task(ctx, mesh_id, paths[mesh_id], roles[mesh_id], prefix, robot)
        for mesh_id in _largest_first(roles, lambda mesh_id: paths[mesh_id])
    ]
    tasks += [
        _decompose_task(ctx, name, *decomposed[name], prefix)
        for name in _largest_first(decomposed, lambda name: paths[decomposed[name][0]])
    ]
    _check_simulation_settings(ctx, part_robot(ctx, robot, parts), plan)
    srdf = _srdf_task(ctx, prefix) if _srdf_source(ctx) else None
    if srdf is not None:
        tasks.append(srdf)
    matrix = None
    if ctx.manifest.self_collision != "none":
        matrix = _selfcollision_task(ctx, plan, robot, choices, roles, decomposed, prefix, parts)
        tasks.append(matrix)
    tasks.append(_assemble_task(ctx, plan, sorted(roles), choices, decomposed, prefix, parts))
    tasks.append(_scene_task(ctx, plan, prefix))
    if ctx.manifest.output.urdf is not None:
        tasks.append(_export_urdf_task(ctx, prefix))
    if ctx.manifest.training is not None:
        colliding = [m for m, r in roles.items() if "collision" in r or "hull" in r]
        tasks.append(_training_task(ctx, plan, colliding, decomposed, prefix))
    if checks:
        tasks.append(_check_task(ctx, prefix, parts))
        if ctx.manifest.check.previews:
            tasks.append(_previews_task(ctx, prefix))
        if ctx.manifest.check.tuning:
            tasks.append(_tuning_task(ctx, prefix))
    if ctx.manifest.output.package:
        tasks.append(_package_task(ctx, prefix, checks))
    if ctx.manifest.output.page:
        tasks.append(_page_task(ctx, prefix))
    return tasks


def _largest_first(names: Iterable[str], source: Callable[[str], str]) -> list[str]:
    """``names`` ordered by the size of each one's ``source`` file, largest first.

    doit starts ready tasks in list order, and a long task started last finishes alone on one
    core while the others wait. A mesh's file size is the only estimate of its work known
    before any mesh is read: it puts go1's 13 MB trunk (2.4 s to convert, the others 0.2 s)
    and g1's torso (its slowest decomposition) among the first.
    """

    def size(name: str) -> int:
        try:
            return Path(source(name)).stat().st_size
        except OSError:
            return 0

    return sorted(names, key=lambda name: (-size(name), name))


def _check_simulation_settings(ctx: BuildContext, robot: Robot, plan: Plan) -> None:
    """Refuse actuator rules and home values that name no joint, before anything is built."""
    from mjcfbuild.control.choose import check_rules
    from mjcfbuild.control.home import home_values
    from mjcfbuild.errors import MjcfbuildError
    from mjcfbuild.manifest.pinpoint import pinpoint

    try:
        check_rules(robot, ctx.manifest.actuators, ctx.manifest_label)
        _motors(ctx)  # an unknown motor or a bad motor file, before anything is built
        control = plan.control()
        home_values(robot, control, ctx.manifest.home, None, ctx.manifest_label)
        _check_kept_pairs(robot, ctx)
        _check_floor_contacts(robot, ctx)
    except MjcfbuildError as error:
        if ctx.manifest_file is not None:
            pinpoint(error, ctx.manifest_label, ctx.manifest_file)
        raise


def _motors(ctx: BuildContext) -> dict[str, dict]:
    """The motors the actuator rules name (control.catalogue), their datasheet values."""
    from mjcfbuild.control.catalogue import resolve_motors

    return resolve_motors(
        ctx.manifest.motors,
        ctx.manifest.actuators.rules,
        ctx.base_dir,
        ctx.manifest_label,
    )


def _check_kept_pairs(robot: Robot, ctx: BuildContext) -> None:
    from mjcfbuild.control.choose import listing
    from mjcfbuild.errors import ManifestError

    settings = ctx.manifest.self_collision
    if settings == "none":
        return
    links = [link.name for link in robot.links]
    for index, pair in enumerate(settings.keep):
        for link in pair:
            if link not in links:
                raise ManifestError(
                    f"link '{link}' is not a link of the robot{did_you_mean(link, links)}",
                    file=f"{ctx.manifest_label} self_collision.keep[{index}]",
                    hint=f"links: {listing(links)}",
                )


def _check_floor_contacts(robot: Robot, ctx: BuildContext) -> None:
    from mjcfbuild.control.choose import listing
    from mjcfbuild.errors import ManifestError

    settings = ctx.manifest.training
    if settings is None:
        return
    links = [link.name for link in robot.links]
    for key in ("add", "remove"):
        for index, link in enumerate(getattr(settings.floor_contacts, key)):
            if link not in links:
                raise ManifestError(
                    f"link '{link}' is not a link of the robot{did_you_mean(link, links)}",
                    file=f"{ctx.manifest_label} output.training.floor_contacts.{key}[{index}]",
                    hint=f"links: {listing(links)}",
                )


SRDF_SUMMARY = "srdf.json"
SELF_COLLISION = "self_collision.json"


def _srdf_home_state(ctx: BuildContext) -> str | None:
    """The SRDF group state that is the home pose, when an SRDF is read."""
    settings = ctx.manifest.self_collision
    return settings.home_state if settings != "none" and settings.srdf else None


def _named_srdf(ctx: BuildContext) -> Path | None:
    """The SRDF robot.yaml names (self_collision.srdf)."""
    settings = ctx.manifest.self_collision
    if settings == "none" or settings.srdf is None:
        return None
    return ctx.resolve(settings.srdf)


def _srdf_source(ctx: BuildContext) -> Path | None:
    """The SRDF the build reads: the one robot.yaml names, else, for a floating robot whose
    home robot.yaml does not give, the one shipped beside the description (for its standing
    pose; see selfcollision.discover)."""
    named = _named_srdf(ctx)
    if named is not None:
        return named
    if not ctx.manifest.options.free_joint or ctx.source_kind == "description":
        return None
    from mjcfbuild.selfcollision.discover import find_srdf

    return find_srdf(ctx.source_path)


def _srdf_task(ctx: BuildContext, prefix: str) -> dict:
    source = _srdf_source(ctx)
    assert source is not None, "only made when there is an SRDF to read"
    named = _named_srdf(ctx) is not None
    if named:
        _require_file(ctx, source, "SRDF", "self_collision.srdf")
    payload = SrdfPayload(
        source=str(source),
        label=ctx.label(source),
        args=ctx.manifest.source.xacro_args if named else {},
        packages=_packages(ctx.resolver.explicit),
        environment=_environment(ctx),
        output=str(ctx.state(SRDF_SUMMARY)),
        discovered=not named,
    )
    return _task(
        ctx,
        f"{prefix}srdf",
        f"srdf {ctx.label(source)}",
        "srdf",
        payload,
        in_worker=source.name.endswith(".xacro"),
        file_dep=[source],
        targets=[ctx.state(SRDF_SUMMARY)],
    )


def _selfcollision_task(
    ctx: BuildContext,
    plan: Plan,
    robot: Robot,
    choices: list[CollisionChoice],
    roles: dict[str, list[str]],
    decomposed: dict[str, tuple[str, dict]],
    prefix: str,
    parts: list[MjcfPartFiles] | None = None,
) -> dict:
    from mjcfbuild.engine.part_tasks import urdf_home
    from mjcfbuild.selfcollision.parts import collision_digest
    from mjcfbuild.selfcollision.robot import collision_robot

    settings = ctx.manifest.self_collision
    assert settings != "none", "only made when self-collision is on"
    meshes = sorted(m for m, r in roles.items() if set(r) - {"visual"})
    decompositions = _decomposition_files(ctx, decomposed)
    srdf = ctx.state(SRDF_SUMMARY) if _srdf_source(ctx) else None
    initial = {
        joint["name"]: joint["initial"]
        for joint in plan.ros2_control.get("joints", [])
        if joint.get("initial") is not None
    }
    payload = SelfCollisionPayload(
        robot=collision_robot(robot, choices).to_dict(),
        choices=[choice.to_dict() for choice in choices],
        fuse_static=ctx.manifest.options.fuse_static,
        free_joint=ctx.manifest.options.free_joint,
        decompositions=decompositions,
        initial=initial,
        home=urdf_home(robot, ctx.manifest.home),  # MJCF parts' joints are not in the matrix
        keep=[list(pair) for pair in settings.keep],
        home_state=settings.home_state,
        settings={
            "samples": settings.samples,
            "seed": settings.seed,
            "exclude_never": settings.exclude_never,
        },
        srdf=str(srdf) if srdf else None,
        products={m: str(product_summary(ctx, m)) for m in meshes},
        product_dirs={m: str(ctx.products_dir / m) for m in meshes},
        manifest_label=ctx.manifest_label,
        cache=ctx.cache_settings(),
        output=str(ctx.state(SELF_COLLISION)),
        mjcf_parts=list(parts or []),
        part_digests=[collision_digest(Path(part.xml), Path(part.summary)) for part in parts or []],
    )
    return _task(
        ctx,
        f"{prefix}selfcollision",
        "self-collision matrix",
        "selfcollision",
        payload,
        in_worker=True,
        file_dep=[
            *(product_summary(ctx, m) for m in meshes),
            *(Path(d.summary) for d in decompositions),
            *([srdf] if srdf else []),
        ],
        targets=[ctx.state(SELF_COLLISION)],
    )


def _decomposition_files(ctx: BuildContext, decomposed: dict) -> list[DecompositionFiles]:
    return [
        DecompositionFiles(
            mesh_id=mesh_id,
            params=params,
            folder=str(decomposition_dir(ctx, name)),
            summary=str(decomposition_dir(ctx, name).with_suffix(".json")),
        )
        for name, (mesh_id, params) in decomposed.items()
    ]


def _task(
    ctx: BuildContext,
    name: str,
    title: str,
    step: str,
    payload: Payload,
    *,
    in_worker: bool,
    file_dep: list[Path],
    targets: list[Path],
    extra_uptodate: list | None = None,
    after: list[str] | None = None,
) -> dict:
    """A doit task running build step ``step`` on ``payload``; up to date while its file
    dependencies, the payload's counted fields and the step's tool versions are unchanged."""
    params = {**payload.uptodate_params(), "versions": step_versions(step)}
    return {
        "task_dep": after or [],
        "name": name,
        "title": lambda _task, title=title: title,
        "doc": title,
        "actions": [
            (_run, [ctx, name, f"mjcfbuild.steps.{step}:run", payload.to_dict(), in_worker])
        ],
        "file_dep": sorted({str(p) for p in file_dep}),
        "targets": [str(p) for p in targets],
        "uptodate": [
            ParamsUnchanged(params),
            outputs_intact(ctx.session.hashes),
            *(extra_uptodate or []),
        ],
        "verbosity": 0,
        "clean": True,
    }


def _run(
    ctx: BuildContext,
    name: str,
    step: str,
    payload: dict,
    in_worker: bool,
    task: Any,  # doit's Task, which doit passes to an action that names a `task` parameter
) -> TaskFailed | dict:
    """The action of every task: run the step, keep its warnings, report its outputs.

    Files the step reports as ``discovered`` (what a xacro expansion included) join the
    task's dependencies before doit records its success, so they are checked from the next
    build on, like the dependencies a compiler writes into a ``.d`` file.
    """
    started = time.perf_counter()
    try:
        result = ctx.session.run_step(step, payload, task=name, in_worker=in_worker)
    except Exception as exc:
        error = ctx.session.record_failure(name, exc)
        ctx.session.task_warnings[name] = []  # it reruns, and warns again, next time
        return TaskFailed(error.one_line())
    finally:
        ctx.session.timings[name] = time.perf_counter() - started
    ctx.session.warnings.extend(result.get("warnings", []))
    ctx.session.task_warnings[name] = list(result.get("warnings", []))
    # What clean may remove: the files the step reports, checked (outputs) or not (written).
    ctx.session.written.update(result["outputs"], result.get("written", []))
    notes = ["from cache" if result.get("cached") else "", result.get("note", "")]
    if any(notes):
        ctx.session.notes[name] = "; ".join(n for n in notes if n)
    if result.get("stored"):
        ctx.session.cache_grew = True
    if "discovered" in result:
        # What this run read replaces what the last run's depfile listed: a file no longer
        # read would otherwise stay in the list doit saves, and the build stage would find
        # the list changed and run the task a second time.
        task.file_dep.intersection_update({payload["source"]})
        task.file_dep.update(result["discovered"])
    return {"outputs": result["outputs"]}


def _require_file(ctx: BuildContext, path: Path, what: str, key: str) -> None:
    """:class:`InputError` unless ``path``, named by manifest key ``key``, is a readable file."""
    problem = unreadable_file(path)
    if problem:
        from mjcfbuild.manifest.pinpoint import key_line

        line = key_line(ctx.manifest_file, key)
        where = f"at {ctx.manifest_label}:{line}" if line else f"in {ctx.manifest_label}"
        raise InputError(f"{what} {problem}", file=ctx.label(path), hint=f"fix '{key}' {where}")


def _packages(packages: dict[str, Path]) -> dict[str, str]:
    return {name: str(path) for name, path in packages.items()}


def _environment(ctx: BuildContext) -> dict[str, str]:
    """The ROS variables package lookup reads, as the build sees them."""
    return {key: ctx.environ.get(key, "") for key in ENV_VARIABLES}


def _expand_task(ctx: BuildContext, prefix: str) -> dict:
    source = ctx.source_path
    _require_file(ctx, source, "source file", f"source.{ctx.source_kind}")
    return expand_file_task(
        ctx,
        f"{prefix}expand",
        source,
        ctx.source_kind,
        ctx.manifest.source.xacro_args,
        ctx.resolver.explicit,
        ctx.state(SOURCE_URDF),
        ctx.state(SOURCE_DEPS),
        args_key=_args_key(ctx, "source.args"),
    )


def _args_key(ctx: BuildContext, key: str) -> str:
    """Where xacro arguments were given, for the error about one no file declares."""
    from mjcfbuild.sources.expand import COMMAND_LINE

    if ctx.manifest_file is None and ctx.manifest_label == COMMAND_LINE:
        return COMMAND_LINE  # convert's NAME:=VALUE
    return f"{ctx.manifest_label} {key}"


def expand_file_task(
    ctx: BuildContext,
    name: str,
    source: Path,
    kind: str,
    args: dict[str, str],
    packages: dict[str, Path],
    output: Path,
    deps: Path,
    args_key: str | None = None,
) -> dict:
    """The task expanding (xacro) or reading (URDF) ``source`` into ``output``; the files it
    read are listed in ``deps`` and checked from the next build on, where each line's element
    was written in :func:`~mjcfbuild.sources.origins.origins_file`. ``args_key`` is where
    ``args`` were given (:func:`~mjcfbuild.sources.expand.expand_xacro`)."""
    from mjcfbuild.sources.origins import origins_file

    depfile = Depfile.read(deps)
    file_dep = [source]
    extra = []
    if depfile is not None:
        stale = depfile.stale_reason(ctx.environ)
        file_dep += [Path(f) for f in depfile.files if Path(f).exists()]
        if stale:
            extra.append(always_stale(stale))
    payload = ExpandPayload(
        kind=kind,
        source=str(source),
        args=args,
        packages=_packages(packages),
        environment=_environment(ctx),
        output=str(output),
        depfile=str(deps),
        origins=str(origins_file(output)),
        args_key=args_key or "",
    )
    return _task(
        ctx,
        name,
        f"expand {ctx.label(source)}",
        "expand",
        payload,
        in_worker=kind == "xacro",
        file_dep=file_dep,
        targets=[output, deps, origins_file(output)],
        extra_uptodate=extra,
    )


def planned_urdf(ctx: BuildContext) -> Path:
    """The URDF the plan reads and the check compares with: the expanded source, or with
    ``attach:`` parts, the source with the parts joined to it."""
    from mjcfbuild.engine.part_tasks import has_urdf_parts

    return ctx.state(COMPOSED_URDF) if has_urdf_parts(ctx.manifest) else ctx.state(SOURCE_URDF)


def _plan_task(ctx: BuildContext, prefix: str) -> dict:
    urdf = planned_urdf(ctx)
    inputs_file = None
    if ctx.manifest.mujoco_inputs.file:
        inputs_file = ctx.resolve(ctx.manifest.mujoco_inputs.file)
        _require_file(ctx, inputs_file, "inputs file", "mujoco_inputs.file")
    expanded = ctx.source_kind == "xacro" or urdf != ctx.state(SOURCE_URDF)
    prebuilt = ctx.prebuilt_mesh_dir  # convert -a
    payload = PlanPayload(
        urdf=str(urdf),
        display=ctx.label(urdf if expanded else ctx.source_path),
        expanded_from=ctx.label(ctx.source_path) if expanded else None,
        base_dir=str(ctx.source_base_dir),
        packages=_packages(ctx.resolver.explicit),
        environment=_environment(ctx),
        inputs_file=str(inputs_file) if inputs_file else None,
        inputs_file_label=ctx.label(inputs_file) if inputs_file else None,
        output=str(ctx.state(PLAN)),
        prebuilt_meshes=str(prebuilt) if prebuilt is not None else None,
        roots=None if ctx.manifest.source.read_outside else _description_roots(ctx),
    )
    return _task(
        ctx,
        f"{prefix}plan",
        "plan",
        "plan",
        payload,
        in_worker=False,
        file_dep=[urdf, *([inputs_file] if inputs_file else [])],
        targets=[ctx.state(PLAN)],
        extra_uptodate=[planned_meshes_exist(ctx.state(PLAN))],
    )


def _description_roots(ctx: BuildContext) -> list[str]:
    """The folders a description reads from without a warning: robot.yaml's, the source
    file's, the packages robot.yaml names, and those of the parts it attaches."""
    from mjcfbuild.engine.part_tasks import part_folders

    folders = [ctx.base_dir, ctx.source_base_dir, *ctx.resolver.explicit.values()]
    return sorted({str(ctx.resolve(str(folder))) for folder in [*folders, *part_folders(ctx)]})


def product_summary(ctx: BuildContext, mesh_id: str) -> Path:
    """Where the summary of a mesh's product is written."""
    return ctx.products_dir / f"{mesh_id}.json"


def _mesh_task(
    ctx: BuildContext, mesh_id: str, path: str, roles: list[str], prefix: str, robot: Robot
) -> dict:
    depfile = Depfile.read(_mesh_depfile(ctx, mesh_id))
    file_dep = [Path(path)]
    extra = []
    if depfile is not None:
        file_dep += [Path(f) for f in depfile.files if Path(f).exists()]
        stale = depfile.stale_reason(ctx.environ)
        if stale:
            extra.append(always_stale(stale))
    meshes = ctx.manifest.meshes
    up_axis = up_axis_mode(meshes.collada_up_axis, meshes.collada_up_axis_files, path)
    options = MeshOptions(
        roles=roles,
        max_faces=meshes.max_faces,
        collada_up_axis=up_axis,
        # Each budget only for the product it shapes, so other products keep their cache keys.
        collision_max_faces=meshes.collision_max_faces if "collision" in roles else None,
        max_hull_vertices=meshes.max_hull_vertices if "hull" in roles else None,
    )
    payload = MeshPayload(
        options=options,
        max_file_bytes=int(meshes.max_file_mb * 1e6),
        source=path,
        product_dir=str(ctx.products_dir / mesh_id),
        summary=str(product_summary(ctx, mesh_id)),
        depfile=str(_mesh_depfile(ctx, mesh_id)),
        cache=ctx.cache_settings(),
        evidence=[u.to_dict() for u in mesh_uses(robot, mesh_id)] if up_axis == "auto" else [],
    )
    return _task(
        ctx,
        f"{prefix}mesh:{mesh_id}",
        f"mesh {mesh_id}",
        "mesh",
        payload,
        in_worker=True,
        file_dep=file_dep,
        targets=[product_summary(ctx, mesh_id)],
        extra_uptodate=extra,
    )


def up_axis_mode(mode: str, files: Mapping[str, str], path: str) -> str:
    """The up-axis option of one mesh file: a ``collada_up_axis_files`` entry matching the end
    of its path, else ``mode``; only DAE files are ever ``auto`` (other formats have no tag,
    and keep the product keys they had before ``auto`` existed)."""
    from fnmatch import fnmatchcase

    posix = path.replace("\\", "/")
    for pattern, choice in sorted(files.items()):
        if fnmatchcase(posix, pattern) or fnmatchcase(posix, "*/" + pattern.lstrip("/")):
            return choice
    if mode == "auto" and not posix.lower().endswith(".dae"):
        return "ignore"
    return mode


def _mesh_depfile(ctx: BuildContext, mesh_id: str) -> Path:
    return ctx.products_dir / f"{mesh_id}.deps.json"


def decomposition_dir(ctx: BuildContext, name: str) -> Path:
    """Where the parts of a decomposition are written."""
    return ctx.state_dir / "decompositions" / name


def _decompose_task(ctx: BuildContext, name: str, mesh_id: str, params: dict, prefix: str) -> dict:
    folder = decomposition_dir(ctx, name)
    payload = DecomposePayload(
        params=params,
        product_summary=str(product_summary(ctx, mesh_id)),
        product_dir=str(ctx.products_dir / mesh_id),
        output_dir=str(folder),
        summary=str(folder.with_suffix(".json")),
        cache=ctx.cache_settings(),
    )
    return _task(
        ctx,
        f"{prefix}decompose:{name}",
        f"decompose {name}",
        "decompose",
        payload,
        in_worker=True,
        file_dep=[product_summary(ctx, mesh_id)],
        targets=[folder.with_suffix(".json")],
    )


def _assemble_task(
    ctx: BuildContext,
    plan: Plan,
    meshes: list[str],
    choices: list,
    decomposed: dict,
    prefix: str,
    parts: list[MjcfPartFiles],
) -> dict:
    options = ctx.manifest.options
    inertia = ctx.manifest.inertia
    source_label = ctx.portable_label(ctx.source_path)
    decompositions = _decomposition_files(ctx, decomposed)
    matrix = ctx.state(SELF_COLLISION) if ctx.manifest.self_collision != "none" else None
    srdf = ctx.state(SRDF_SUMMARY) if _srdf_source(ctx) else None
    payload = AssemblePayload(
        choices=[choice.to_dict() for choice in choices],
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
        srdf_home=_srdf_home_state(ctx),
        fuse_static=options.fuse_static,
        free_joint=options.free_joint,
        link_sites=options.link_sites,
        max_hull_vertices=ctx.manifest.meshes.max_hull_vertices,
        inertia={
            "mode": inertia.policy,
            "min_mass": inertia.min_mass,
            "min_inertia": inertia.min_inertia,
        },
        header=f"Generated by mjcfbuild from {source_label}; edit the sources, not this file.",
        assets_dir=str(ctx.assets_dir),
        self_collision=str(matrix) if matrix else None,
        srdf=str(srdf) if srdf else None,
        plan=str(ctx.state(PLAN)),
        products={mesh_id: str(product_summary(ctx, mesh_id)) for mesh_id in meshes},
        product_dirs={mesh_id: str(ctx.products_dir / mesh_id) for mesh_id in meshes},
        manifest_label=ctx.manifest_label,
        report=str(ctx.state(ASSEMBLY_REPORT)),
        floor_record=str(ctx.state(FLOOR_RECORD)),
        output=str(ctx.robot_path),
        mjcf_parts=parts,
    )
    return _task(
        ctx,
        f"{prefix}assemble",
        f"assemble {ctx.manifest.robot_file}",
        "assemble",
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


CHECK_RESULTS = "check.json"
REFERENCE = "reference.json"  # what the check's independent reader read from the URDF


def report_dir(ctx: BuildContext) -> Path:
    """Where the human report, report.json and the previews go."""
    return ctx.out_dir / "report"


def check_payload(
    ctx: BuildContext, parts: list[MjcfPartFiles], options: dict | None = None
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
    )


def _check_task(ctx: BuildContext, prefix: str, parts: list[MjcfPartFiles]) -> dict:
    payload = check_payload(ctx, parts)
    return _task(
        ctx,
        f"{prefix}check",
        f"check {ctx.manifest.robot_file}",
        "check",
        payload,
        in_worker=True,
        file_dep=[
            ctx.robot_path,
            ctx.scene_path,
            ctx.state(PLAN),
            ctx.state(ASSEMBLY_REPORT),
            ctx.state(REFERENCE),
            *(Path(path) for part in parts for path in (part.xml, part.summary)),
        ],
        targets=[ctx.state(CHECK_RESULTS)],
    )


def _reference_task(ctx: BuildContext, prefix: str) -> dict:
    """The check's independent reading of the URDF's kinematics: reruns only when they
    change (check.reference.kinematic_digest), not for a damping or inertia edit."""
    from mjcfbuild.check.reference import kinematic_digest

    urdf = planned_urdf(ctx)
    payload = ReferencePayload(
        urdf=str(urdf),
        kinematics=kinematic_digest(urdf.read_bytes()),
        output=str(ctx.state(REFERENCE)),
    )
    return _task(
        ctx,
        f"{prefix}reference",
        "reference kinematics",
        "reference",
        payload,
        in_worker=True,
        file_dep=[],
        targets=[ctx.state(REFERENCE)],
    )


def _previews_task(ctx: BuildContext, prefix: str) -> dict:
    folder = report_dir(ctx) / "previews"
    # The scene: the robot at home, on its floor.
    payload = PreviewsPayload(
        folder=str(folder),
        model=str(ctx.scene_path),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        record=str(ctx.state(PREVIEWS_RECORD)),
    )
    return _task(
        ctx,
        f"{prefix}previews",
        "previews",
        "previews",
        payload,
        in_worker=True,
        # Not the model file: only what a picture shows (a damping change leaves them alone),
        # and the scene, whose floor the pictures show.
        file_dep=[ctx.scene_path],
        targets=[ctx.state(PREVIEWS_RECORD)],
        extra_uptodate=[RenderInputsUnchanged(ctx.robot_path, ctx.assets_dir, ctx.session.hashes)],
        after=[f"{prefix}assemble"],
    )


def _tuning_task(ctx: BuildContext, prefix: str) -> dict:
    """The tuning report (check.tuning): reruns when the model or its actuators change, and
    alone: neither the check nor the previews wait for it."""
    payload = TuningPayload(
        folder=str(report_dir(ctx) / "tuning"),
        rules=[rule.model_dump(mode="json") for rule in ctx.manifest.actuators.rules],
        model=str(ctx.robot_path),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        record=str(ctx.state(TUNING_RECORD)),
    )
    return _task(
        ctx,
        f"{prefix}tuning",
        "tuning report",
        "tuning",
        payload,
        in_worker=True,
        file_dep=[ctx.robot_path, ctx.state(ASSEMBLY_REPORT)],
        targets=[ctx.state(TUNING_RECORD)],
        after=[f"{prefix}assemble"],
    )


def _package_task(ctx: BuildContext, prefix: str, checked: bool) -> dict:
    from mjcfbuild.package.documents import find_license, git_revision
    from mjcfbuild.steps.versions import tool_version

    folder = ctx.out_dir / PACKAGE_FOLDER
    revision, remote = git_revision(ctx.base_dir)
    top = _git_top(ctx.base_dir) if revision else None
    package_folders = [ctx.resolve(path) for path in ctx.manifest.packages.values()]
    license_file = find_license([ctx.source_base_dir, *package_folders, ctx.base_dir], top)
    picture = report_dir(ctx) / "previews" / "three_quarter_visual.png"
    with_picture = checked and ctx.manifest.check.previews
    payload = PackagePayload(
        name=ctx.manifest.name,
        provenance={
            "source": ctx.portable_label(ctx.source_path),
            "manifest_text": ctx.manifest_file.read_text() if ctx.manifest_file else "",
            "revision": revision,
            "remote": remote,
            "mujoco_version": tool_version("mujoco"),
            "license_from": _license_label(ctx, license_file),
        },
        model=str(ctx.robot_path),
        scene=str(ctx.scene_path),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        assets=str(ctx.assets_dir),
        check=str(ctx.state(CHECK_RESULTS)) if checked else None,
        picture=str(picture) if with_picture else None,
        license=str(license_file) if license_file else None,
        folder=str(folder),
        record=str(ctx.state(PACKAGE_RECORD)),
    )
    optional = [payload.check, payload.picture, payload.license]
    after = [f"{prefix}assemble", f"{prefix}scene"]
    after += [f"{prefix}check"] if checked else []
    after += [f"{prefix}previews"] if with_picture else []
    return _task(
        ctx,
        f"{prefix}package",
        f"package {PACKAGE_FOLDER}/",
        "package",
        payload,
        in_worker=True,
        file_dep=[
            ctx.robot_path,
            ctx.scene_path,
            ctx.state(ASSEMBLY_REPORT),
            *(Path(path) for path in optional if path),
        ],
        targets=[
            ctx.state(PACKAGE_RECORD),
            folder / "README.md",
            folder / ctx.manifest.robot_file,
            folder / "scene.xml",
        ],
        after=after,
    )


def _page_task(ctx: BuildContext, prefix: str) -> dict:
    """The interactive report page (output.page): the model's files and MuJoCo's WebAssembly
    build bundled beside the report. The report's tables are not its input: the build writes
    them with the report (engine/report.py), failed checks included, which a failed check task
    would stop a task after it from doing."""
    from mjcfbuild.page import web_files
    from mjcfbuild.page.vendor import INTEGRITY, VERSION

    folder = report_dir(ctx)
    payload = PagePayload(
        name=ctx.manifest.name,
        mujoco_js=f"{VERSION} {INTEGRITY}",
        model=str(ctx.robot_path),
        scene=str(ctx.scene_path),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        assets=str(ctx.assets_dir),
        hold_tolerance=ctx.manifest.check.hold_tolerance,
        folder=str(folder),
    )
    return _task(
        ctx,
        f"{prefix}page",
        "report page report/index.html",
        "page",
        payload,
        in_worker=False,  # no MuJoCo, no native code: files read, encoded and written
        file_dep=[
            ctx.robot_path,
            ctx.scene_path,
            ctx.state(ASSEMBLY_REPORT),
            *web_files(),  # the page's template, script and style
        ],
        targets=[folder / name for name in PAGE_FILES],
        after=[f"{prefix}assemble", f"{prefix}scene"],
    )


def _license_label(ctx: BuildContext, license_file: Path | None) -> str:
    """How the README names the license file: relative to robot.yaml when inside its folder,
    else by its folder and name (``panda_description/LICENSE``), the same on every machine."""
    if license_file is None:
        return ""
    label = ctx.portable_label(license_file)
    if label.startswith("../"):
        return f"{license_file.parent.name}/{license_file.name}"
    return label


def _git_top(folder: Path) -> Path | None:
    import subprocess

    result = subprocess.run(
        ["git", "-C", str(folder), "rev-parse", "--show-toplevel"],
        capture_output=True,
        text=True,
        check=False,
    )
    return Path(result.stdout.strip()).resolve() if result.returncode == 0 else None


def _export_urdf_task(ctx: BuildContext, prefix: str) -> dict:
    export = ctx.manifest.output.urdf
    urdf, mesh_dir = ctx.urdf_path, ctx.urdf_mesh_dir
    assert export is not None and urdf is not None and mesh_dir is not None
    assert not isinstance(export, str), "validation makes a file name a UrdfExport"
    payload = ExportUrdfPayload(
        options={
            "asset_prefix": export.asset_prefix,
            "sites": export.sites,
            "mesh_folder": export.mesh_folder,
            "header": f"Generated by mjcfbuild from {ctx.manifest.robot_file}; "
            "edit the sources, not this file.",
        },
        model=str(ctx.robot_path),
        plan=str(ctx.state(PLAN)),
        assembly_report=str(ctx.state(ASSEMBLY_REPORT)),
        urdf=str(urdf),
        mesh_dir=str(mesh_dir),
        record=str(ctx.state(URDF_EXPORT_RECORD)),
    )
    return _task(
        ctx,
        f"{prefix}export_urdf",
        f"export {export.file}",
        "export_urdf",
        payload,
        in_worker=True,
        file_dep=[ctx.robot_path, ctx.state(PLAN), ctx.state(ASSEMBLY_REPORT)],
        targets=[urdf],
    )


def _scene_payload(ctx: BuildContext, plan: Plan, robot_file: str, output: Path) -> ScenePayload:
    """The scene around ``robot_file`` (the model, or the training variant)."""
    scene = ctx.manifest.scene
    source = ctx.resolve(scene.file) if scene.file else None
    if source is not None:
        _require_file(ctx, source, "scene file", "scene.file")
    block = None
    if scene.mjcf:
        # The manifest relative to its own folder: the same parameter whichever folder the
        # build runs in (errors are shown relative to the current folder when reported).
        where = ctx.portable_label(ctx.manifest_file) if ctx.manifest_file else ctx.manifest_label
        block = {"xml": scene.mjcf, "origin": f"{where} scene.mjcf"}
    elif source is None:
        for where in ("file", "urdf"):
            found = (plan.inputs.get(where) or {}).get("scene")
            if found:
                block = found
                break
    return ScenePayload(
        scene_file=str(source) if source else None,
        scene_block=block,
        model=ctx.manifest.name,
        robot_file=robot_file,
        floor=ctx.manifest.placement.floor,
        floor_record=str(ctx.state(FLOOR_RECORD)),
        output=str(output),
    )


def _scene_task(ctx: BuildContext, plan: Plan, prefix: str) -> dict:
    payload = _scene_payload(ctx, plan, ctx.manifest.robot_file, ctx.scene_path)
    source = Path(payload.scene_file) if payload.scene_file else None
    auto_floor = ctx.manifest.placement.floor == "auto"
    return _task(
        ctx,
        f"{prefix}scene",
        f"scene {ctx.manifest.output.scene}",
        "scene",
        payload,
        in_worker=False,
        file_dep=([source] if source else []) + ([ctx.state(FLOOR_RECORD)] if auto_floor else []),
        targets=[ctx.scene_path],
        # Outputs change together: a build whose model fails leaves the scene alone too.
        after=[f"{prefix}assemble"],
    )


TRAINING_RECORD = "training.json"


def training_paths(ctx: BuildContext) -> tuple[Path, Path]:
    """The training variant's file and its scene's."""
    files = ctx.manifest.training_files
    assert files is not None, "asked only when robot.yaml sets output.training"
    return ctx.out_dir / files[0], ctx.out_dir / files[1]


def _training_task(
    ctx: BuildContext, plan: Plan, colliding: list[str], decomposed: dict, prefix: str
) -> dict:
    """The training variant: made from the assembled model (so it shares the mesh products,
    the matrix, actuators and home), rerun when the model, the matrix, its settings or the
    products of meshes that collide change (the model names its assets by file, so a changed
    collision mesh leaves the model's text alone); an edit to a mesh that is only drawn
    leaves the variant as it is, since it refers to the same asset file."""
    settings = ctx.manifest.training
    assert settings is not None
    variant, scene_path = training_paths(ctx)
    matrix = ctx.state(SELF_COLLISION) if ctx.manifest.self_collision != "none" else None
    scene_payload = _scene_payload(ctx, plan, variant.name, scene_path)
    source = scene_payload.scene_file
    auto_floor = ctx.manifest.placement.floor == "auto"
    payload = TrainingPayload(
        settings={
            "floor_add": list(settings.floor_contacts.add),
            "floor_remove": list(settings.floor_contacts.remove),
            "self_contacts": settings.self_contacts,
            "max_hull_vertices": settings.max_hull_vertices,
            "primitive_fit": settings.primitive_fit,
            "device": settings.device,
            "solver": settings.solver,
            "iterations": settings.iterations,
            "ls_iterations": settings.ls_iterations,
            "timestep": settings.timestep,
            "frictionloss": settings.frictionloss,
            "dcmotor": settings.dcmotor,
            "label": f"{ctx.manifest_label} output.training",
        },
        header=f"Training variant generated by mjcfbuild from {ctx.manifest.robot_file}; "
        "edit the sources, not this file.",
        model=str(ctx.robot_path),
        self_collision=str(matrix) if matrix else None,
        robot_file=ctx.manifest.robot_file,
        scene=scene_payload,
        output=str(variant),
        record=str(ctx.state(TRAINING_RECORD)),
    )
    return _task(
        ctx,
        f"{prefix}training",
        f"training variant {variant.name}",
        "training",
        payload,
        in_worker=True,
        file_dep=[
            ctx.robot_path,
            *(product_summary(ctx, mesh_id) for mesh_id in colliding),
            *(Path(d.summary) for d in _decomposition_files(ctx, decomposed)),
            *([matrix] if matrix else []),
            *([Path(source)] if source else []),
            *([ctx.state(FLOOR_RECORD)] if auto_floor else []),
        ],
        targets=[variant, scene_path, ctx.state(TRAINING_RECORD)],
        after=[f"{prefix}assemble"],
    )
