"""The tasks of ``attach:`` parts: one task per part, then the composition (the ``mjcfpart``
and ``compose`` task families).

Each URDF or xacro part is expanded by a task of its own (``expand:<prefix>``), so editing a
gripper's xacro re-expands the gripper alone; the ``compose`` task joins the expanded parts to
the expanded main source, and the plan reads its result. Mesh tasks are per mesh file as always,
so the arm's meshes stay up to date when the gripper changes.

Each MJCF part is read, compiled alone and normalised by a task of its own (``part:<prefix>``,
in the planning stage, so its joints are known before anything is built); the ``assemble`` task
attaches the normalised parts and the ``check`` task compares them with the parts compiled alone.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import ManifestError, MjcfbuildError
from mjcfbuild.families.expand import expand_file_task
from mjcfbuild.fsutil import unreadable_file
from mjcfbuild.graph.family import Family, discovered_inputs, file_task, ros_environment
from mjcfbuild.outputs import COMPOSED_URDF, SOURCE_URDF, mjcf_part_paths, part_urdf
from mjcfbuild.sources.packages import did_you_mean
from mjcfbuild.steps.payloads import ComposePayload, MjcfPartFiles, MjcfPartPayload, PartEntry

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph
    from mjcfbuild.manifest.composition import Attachment
    from mjcfbuild.urdf.model import Robot


def _mjcf_part_tasks(graph: Graph) -> list[dict]:
    """One ``part:`` task per MJCF part; none without them."""
    return [
        _mjcf_part_task(graph.ctx, graph.prefix, index, part)
        for index, part in enumerate(graph.ctx.manifest.attach)
        if part.source.kind == "mjcf"
    ]


def _composition_tasks(graph: Graph) -> list[dict]:
    """An ``expand:`` task per URDF or xacro part, and the ``compose`` task; none without."""
    from mjcfbuild.sources.origins import origins_file

    ctx, prefix = graph.ctx, graph.prefix
    tasks: list[dict] = []
    parts = [(i, part) for i, part in enumerate(ctx.manifest.attach) if part.source.kind != "mjcf"]
    if not parts:
        return tasks
    entries: list[PartEntry] = []
    for index, part in parts:
        source = _part_source(ctx, index, part)
        packages = _part_packages(ctx, index, part)
        output = part_urdf(ctx, index)
        tasks.append(
            expand_file_task(
                ctx,
                f"{prefix}expand:{part.prefix}",
                source,
                part.source.kind,
                part.source.xacro_args,
                packages,
                output,
                output.with_suffix(".deps.json"),
                args_key=f"{ctx.manifest_label} attach[{index}].source.args",
            )
        )
        entries.append(
            PartEntry(
                urdf=str(output),
                label=ctx.label(output if part.source.kind == "xacro" else source),
                key=f"{ctx.manifest_label} attach[{index}]",
                prefix=part.prefix,
                to=part.to,
                xyz=list(part.pos),
                rpy=list(part.rpy),
                base_dir=str(source.parent),
                packages={name: str(path) for name, path in packages.items()},
            )
        )
    payload = ComposePayload(
        main=str(ctx.state(SOURCE_URDF)),
        main_label=ctx.label(
            ctx.state(SOURCE_URDF) if ctx.source_kind == "xacro" else ctx.source_path
        ),
        base_dir=str(ctx.source_base_dir),
        parts=entries,
        environment=ros_environment(ctx),
        output=str(ctx.state(COMPOSED_URDF)),
        origins=str(origins_file(ctx.state(COMPOSED_URDF))),
    )
    inputs = [ctx.state(SOURCE_URDF), *(Path(e.urdf) for e in entries)]
    tasks.append(
        file_task(
            ctx,
            COMPOSE,
            f"{prefix}compose",
            f"attach {', '.join(part.prefix for _, part in parts)}",
            payload,
            in_worker=False,
            # The inputs' origins too: a xacro line that moved moves the composed origins.
            file_dep=[
                *(p for e in inputs for p in (e, origins_file(e))),
            ],
            targets=[ctx.state(COMPOSED_URDF), origins_file(ctx.state(COMPOSED_URDF))],
        )
    )
    return tasks


def part_folders(ctx: GraphContext) -> list[Path]:
    """The folders the URDF and xacro parts read their files from: each part file's folder
    and the packages robot.yaml names for it."""
    folders: list[Path] = []
    for index, part in enumerate(ctx.manifest.attach):
        if part.source.kind != "mjcf":
            folders.append(ctx.resolve(part.source.file).parent)
            folders += _part_packages(ctx, index, part).values()
    return folders


def _part_source(ctx: GraphContext, index: int, part: Attachment) -> Path:
    source = ctx.resolve(part.source.file)
    problem = unreadable_file(source)
    if problem:
        raise _pinpointed(
            ctx,
            ManifestError(
                f"part file {problem}",
                file=f"{ctx.manifest_label} attach[{index}].source.{part.source.kind}",
                hint="fix the path (relative to robot.yaml)",
            ),
        )
    return source


def _part_packages(ctx: GraphContext, index: int, part: Attachment) -> dict[str, Path]:
    """The build's packages with the part's own over them."""
    packages = dict(ctx.resolver.explicit)
    for name, folder in sorted(part.packages.items()):
        path = ctx.resolve(folder)
        if not path.is_dir():
            raise _pinpointed(
                ctx,
                ManifestError(
                    f"package '{name}' points at '{folder}', which is not a folder",
                    file=f"{ctx.manifest_label} attach[{index}].packages.{name}",
                    hint="fix the folder (relative to robot.yaml) or remove the entry",
                ),
            )
        packages[name] = path
    return packages


def _pinpointed(ctx: GraphContext, error: MjcfbuildError) -> MjcfbuildError:
    from mjcfbuild.manifest.pinpoint import pinpoint

    if ctx.manifest_file is not None:
        pinpoint(error, ctx.manifest_label, ctx.manifest_file)
    return error


def _mjcf_part_task(ctx: GraphContext, prefix: str, index: int, part: Attachment) -> dict:
    source = _part_source(ctx, index, part)
    paths = mjcf_part_paths(ctx, index)
    read, stale = discovered_inputs(ctx, paths["depfile"])
    payload = MjcfPartPayload(
        source=str(source),
        label=ctx.label(source),
        assets_dir=str(paths["assets_dir"]),
        xml=str(paths["xml"]),
        summary=str(paths["summary"]),
        depfile=str(paths["depfile"]),
    )
    return file_task(
        ctx,
        MJCFPART,
        f"{prefix}part:{part.prefix}",
        f"part {ctx.label(source)}",
        payload,
        in_worker=True,
        file_dep=[source, *read],
        targets=[paths["xml"], paths["summary"]],
        extra_uptodate=stale,
    )


def mjcf_parts(ctx: GraphContext, robot: Robot) -> list[MjcfPartFiles]:
    """The MJCF parts as the assemble and check tasks take them, in the order they can be
    attached (a part may attach to a body of another). Refuses, before anything is built, a
    ``to`` that names nothing of the model, parts attached to each other in a cycle and a
    prefix that makes a name collide."""
    from mjcfbuild.compose.mjcf import PartSummary

    pending = []
    for index, part in enumerate(ctx.manifest.attach):
        if part.source.kind != "mjcf":
            continue
        paths = mjcf_part_paths(ctx, index)
        summary = PartSummary.from_dict(json.loads(paths["summary"].read_text()))
        pending.append((index, part, paths, summary))
    if not pending:
        return []
    links = [link.name for link in robot.links]
    known = {"body": set(links), "site": set(links), "joint": {j.name for j in robot.joints}}
    known["actuator"] = set(known["joint"])  # generated actuators are named after joints
    targets = list(links)
    ordered: list[MjcfPartFiles] = []
    while pending:
        ready = [entry for entry in pending if entry[1].to in targets]
        if not ready:
            raise _pinpointed(ctx, _unplaceable(ctx, pending, targets))
        for index, part, paths, summary in ready:
            _check_names(ctx, index, part, summary, known)
            targets += [part.prefix + n for n in (*summary.bodies, *summary.sites)]
            ordered.append(
                MjcfPartFiles(
                    key=f"{ctx.manifest_label} attach[{index}]",
                    prefix=part.prefix,
                    to=part.to,
                    pos=list(part.pos),
                    quat=list(part.orientation),
                    label=summary.label,
                    source=str(ctx.resolve(part.source.file)),
                    xml=str(paths["xml"]),
                    summary=str(paths["summary"]),
                )
            )
            pending.remove((index, part, paths, summary))
    return ordered


def _check_names(
    ctx: GraphContext, index: int, part: Attachment, summary, known: dict[str, set[str]]
) -> None:
    for kind, seen in known.items():
        names = {part.prefix + name for name in summary.names.get(kind, [])}
        clashes = sorted(names & seen)
        if clashes:
            raise _pinpointed(
                ctx,
                ManifestError(
                    f"prefix '{part.prefix}' makes {kind} name '{clashes[0]}' of "
                    f"{summary.label} collide with a name of the model",
                    file=f"{ctx.manifest_label} attach[{index}].prefix",
                    hint="choose a prefix no name of the model starts with",
                ),
            )
        seen |= names


def _unplaceable(ctx: GraphContext, pending: list, targets: list[str]) -> ManifestError:
    """Why none of ``pending`` can be attached: an unknown ``to``, or a cycle."""
    from mjcfbuild.control.choose import listing

    owner = {
        part.prefix + name: (index, part)
        for index, part, _, summary in pending
        for name in (*summary.bodies, *summary.sites)
    }
    chain = [(pending[0][0], pending[0][1])]
    while chain[-1][1].to in owner and owner[chain[-1][1].to] not in chain:
        chain.append(owner[chain[-1][1].to])
    index, last = chain[-1]
    if last.to not in owner:
        return ManifestError(
            f"'to' names '{last.to}', which is not a link of the model nor a body or site of "
            f"an MJCF part{did_you_mean(last.to, set(targets))}",
            file=f"{ctx.manifest_label} attach[{index}].to",
            hint=f"links: {listing(targets)}",
        )
    cycle = chain[chain.index(owner[last.to]) :]
    steps = " -> ".join(f"{part.prefix} (to {part.to})" for _, part in cycle)
    return ManifestError(
        f"parts are attached to each other in a cycle: {steps}",
        file=f"{ctx.manifest_label} attach[{cycle[0][0]}].to",
        hint="attach one of them to a link of the main source",
    )


def part_robot(ctx: GraphContext, robot: Robot, parts: list[MjcfPartFiles]) -> Robot:
    """``robot`` with the MJCF parts' hinge and slide joints, as home patterns and actuator
    rules may name them."""
    from dataclasses import replace

    from mjcfbuild.compose.mjcf import PartSummary, part_joints_as_urdf

    joints = []
    for entry in parts:
        summary = PartSummary.from_dict(json.loads(Path(entry.summary).read_text()))
        joints += part_joints_as_urdf(summary, entry.prefix)
    return replace(robot, joints=[*robot.joints, *joints]) if joints else robot


def urdf_home(robot: Robot, home: dict[str, float]) -> dict[str, float]:
    """The ``home`` patterns that name joints of the URDF model (not only MJCF parts')."""
    from mjcfbuild.control.choose import matches

    moving = [joint.name for joint in robot.joints if joint.moves]
    return {
        pattern: value
        for pattern, value in home.items()
        if any(matches(name, [pattern]) for name in moving)
    }


MJCFPART = Family(
    name="mjcfpart",
    step="mjcfbuild.steps.mjcfpart:run",
    payload=MjcfPartPayload,
    format=1,
    tools=("mujoco", "lxml"),
    tasks=_mjcf_part_tasks,
    stage="planning",
)
COMPOSE = Family(
    name="compose",
    step="mjcfbuild.steps.compose:run",
    payload=ComposePayload,
    format=2,  # 2: the origins of the composed lines
    tools=("lxml",),
    tasks=_composition_tasks,
    stage="planning",
)
