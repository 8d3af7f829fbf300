"""The ``mjcfpart`` family: each MJCF part of ``attach:`` read, compiled alone and normalised
by a task of its own (``part:<prefix>``, in the planning stage, so its joints are known before
anything is built); the ``assemble`` task attaches the normalised parts and the ``check`` task
compares them with the parts compiled alone."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import ManifestError
from mjcfbuild.families.parts import part_source, pinpointed
from mjcfbuild.graph.family import Family, discovered_inputs, file_task
from mjcfbuild.outputs import mjcf_part_paths
from mjcfbuild.sources.packages import did_you_mean
from mjcfbuild.steps.payloads import MjcfPartFiles, MjcfPartPayload

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


def _mjcf_part_task(ctx: GraphContext, prefix: str, index: int, part: Attachment) -> dict:
    source = part_source(ctx, index, part)
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
        FAMILY,
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
            raise pinpointed(ctx, _unplaceable(ctx, pending, targets))
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
            raise pinpointed(
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
    from mjcfbuild.compose.chain import stuck_chain
    from mjcfbuild.sources.packages import listing

    owner = {
        part.prefix + name: (index, part)
        for index, part, _, summary in pending
        for name in (*summary.bodies, *summary.sites)
    }
    (index, last), cycle = stuck_chain(
        (pending[0][0], pending[0][1]), owner, lambda entry: entry[1].to
    )
    if cycle is None:
        return ManifestError(
            f"'to' names '{last.to}', which is not a link of the model nor a body or site of "
            f"an MJCF part{did_you_mean(last.to, set(targets))}",
            file=f"{ctx.manifest_label} attach[{index}].to",
            hint=f"links: {listing(targets)}",
        )
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


FAMILY = Family(
    name="mjcfpart",
    step="mjcfbuild.steps.mjcfpart:run",
    payload=MjcfPartPayload,
    # 2: a joint axis given at any length written as its unit axis at 12 digits; a joint
    # without a name named after its body
    format=2,
    tools=("mujoco", "lxml"),
    tasks=_mjcf_part_tasks,
    stage="planning",
)
