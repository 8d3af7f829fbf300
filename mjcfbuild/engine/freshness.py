"""Are the outputs in an output folder still what their inputs build? Answered without
touching them.

Where the folder has its build database (a working copy someone built in), doit's own
up-to-date test answers it, task by task, with the reason. In a fresh clone (outputs committed,
no database), the build runs into a temporary folder - fast, through the shared cache - and its
files are compared byte for byte with the committed ones.
"""

from __future__ import annotations

import tempfile
from dataclasses import replace
from pathlib import Path

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.loader import DATABASE
from mjcfbuild.families.registry import CHECK_ONLY_TASKS, REPORT_TASKS
from mjcfbuild.outputs import PACKAGE_CHANGELOG, PACKAGE_FOLDER, PLAN


def stale_outputs(ctx: BuildContext) -> list[str]:
    """What is stale, one line each; empty when everything is up to date."""
    if ctx.state(DATABASE).exists() and ctx.state(PLAN).exists():
        return _from_database(ctx)
    return _by_rebuilding(ctx)


def stale_from_database(ctx: BuildContext) -> list[str]:
    """What is stale as the folder's build database tells it (one line each); empty when
    everything is up to date, or the folder has no database (a fresh clone) to tell by."""
    if ctx.state(DATABASE).exists() and ctx.state(PLAN).exists():
        return _from_database(ctx)
    return []


def report_behind(ctx: BuildContext) -> list[str]:
    """The report's tasks (check, previews, tuning) that have not run since their inputs
    changed, by their titles, as the folder's build database tells (a build cut short after
    the model): the model is current, its report is not. Empty without a database."""
    if not (ctx.state(DATABASE).exists() and ctx.state(PLAN).exists()):
        return []
    if not ctx.manifest.check.enabled:
        return []
    from mjcfbuild.engine.status import build_statuses

    statuses, _ = build_statuses(replace(ctx, run_check=True))
    return [
        status.title
        for status in statuses
        if not status.up_to_date and status.name.split(":")[0] in REPORT_TASKS
    ]


def _from_database(ctx: BuildContext) -> list[str]:
    """The stale tasks of the graph ``mjcfbuild build`` (and ``build -n``, ``explain``) plans,
    the check's included: a task that reads the check's results (the package's README, its
    picture) is planned with them, as the build that wrote it planned it. The tasks only the
    check needs write no output of the model, and are not counted."""
    from mjcfbuild.engine.outputs_off import stale_lines
    from mjcfbuild.engine.status import build_statuses

    statuses, _ = build_statuses(replace(ctx, run_check=True))
    return [
        f"{status.title}: {'; '.join(status.reasons)}"
        for status in statuses
        if not status.up_to_date and status.name.split(":")[0] not in CHECK_ONLY_TASKS
    ] + stale_lines(ctx)


def _by_rebuilding(ctx: BuildContext) -> list[str]:
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import run_build

    with tempfile.TemporaryDirectory(prefix="mjcfbuild-fresh-") as scratch:
        # Without the check, unless the package's README and picture read what it finds.
        shadow = replace(
            ctx,
            output_override=Path(scratch) / "out",
            run_check=bool(ctx.manifest.output.package),
        )
        result = run_build(shadow, Progress(quiet=True))
        if result.errors:
            return [f"the inputs do not build: {result.errors[0].one_line()}"]
        return _compare(ctx.out_dir, shadow.out_dir, ctx)


# The package's CHANGELOG: its history of earlier builds, kept across builds, not built anew.
_KEPT = f"{PACKAGE_FOLDER}/{PACKAGE_CHANGELOG}"


def _files(folder: Path) -> dict[str, Path]:
    if not folder.is_dir():
        return {}
    return {
        str(path.relative_to(folder)): path
        for path in folder.rglob("*")
        if path.is_file()
        and not {".mjcfbuild", "report"} & set(path.relative_to(folder).parts)
        and not path.name.startswith(".")
        and path.relative_to(folder).as_posix() != _KEPT
    }


# The package's README: its revision line names the commit as of the package's last change,
# which a commit of the package itself moves on; no input of the model (docs/package.md).
_README = f"{PACKAGE_FOLDER}/README.md"
_REVISION = b"- revision: "


def _comparable(name: str, path: Path) -> bytes:
    """The bytes of ``path`` (``name`` in its folder) that its inputs decide."""
    data = path.read_bytes()
    if name != _README:
        return data
    return b"".join(line for line in data.splitlines(True) if not line.startswith(_REVISION))


def _compare(actual: Path, expected: Path, ctx: BuildContext) -> list[str]:
    have, want = _files(actual), _files(expected)
    stale = []
    for name in sorted(want):
        label = ctx.label(actual / name)
        if name not in have:
            stale.append(f"{label} is missing")
        elif _comparable(name, have[name]) != _comparable(name, want[name]):
            stale.append(f"{label} differs from what its inputs build")
    for name in sorted(set(have) - set(want)):
        stale.append(f"{ctx.label(actual / name)} is no longer built")
    return stale
