"""The tasks of ``attach:`` parts: one expansion per part, then the composition.

Each part is expanded by a task of its own (``expand:<prefix>``), so editing a gripper's xacro
re-expands the gripper alone; the ``compose`` task joins the expanded parts to the expanded main
source, and the plan reads its result. Mesh tasks are per mesh file as always, so the arm's
meshes stay up to date when the gripper changes.
"""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.errors import ManifestError, MjcfbuildError
from mjcfbuild.fsutil import unreadable_file
from mjcfbuild.manifest.composition import Attachment
from mjcfbuild.sources.packages import ENV_VARIABLES
from mjcfbuild.steps.payloads import ComposePayload, PartEntry

PARTS_DIR = "attach"


def composition_tasks(ctx: BuildContext, prefix: str) -> list[dict]:
    """The part expansions and the ``compose`` task; none without ``attach:``."""
    from mjcfbuild.engine.tasks import COMPOSED_URDF, SOURCE_URDF, _task, expand_file_task

    parts = ctx.manifest.attach
    if not parts:
        return []
    tasks = []
    entries: list[PartEntry] = []
    for index, part in enumerate(parts):
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
        environment={key: ctx.environ.get(key, "") for key in ENV_VARIABLES},
        output=str(ctx.state(COMPOSED_URDF)),
    )
    tasks.append(
        _task(
            ctx,
            f"{prefix}compose",
            f"attach {', '.join(part.prefix for part in parts)}",
            "compose",
            payload,
            in_worker=False,
            file_dep=[ctx.state(SOURCE_URDF), *(Path(e.urdf) for e in entries)],
            targets=[ctx.state(COMPOSED_URDF)],
        )
    )
    return tasks


def part_urdf(ctx: BuildContext, index: int) -> Path:
    """Where the expanded URDF of part ``index`` is kept."""
    return ctx.state_dir / PARTS_DIR / f"{index}.urdf"


def _part_source(ctx: BuildContext, index: int, part: Attachment) -> Path:
    source = ctx.resolve(part.source.xacro or part.source.urdf or "")
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


def _part_packages(ctx: BuildContext, index: int, part: Attachment) -> dict[str, Path]:
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


def _pinpointed(ctx: BuildContext, error: MjcfbuildError) -> MjcfbuildError:
    from mjcfbuild.manifest.pinpoint import pinpoint

    if ctx.manifest_file is not None:
        pinpoint(error, ctx.manifest_label, ctx.manifest_file)
    return error
