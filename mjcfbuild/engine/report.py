"""The build report: ``report/report.json`` and ``report/report.md`` in the output folder.

This module gathers what the build steps recorded - each task family's part (its ``report``:
the check results, inertia repairs, mesh statistics, the products, the preview pictures), and
the warnings of the tasks that made the outputs - into one machine-readable file;
:mod:`mjcfbuild.check.report_page` renders the page people read. Both are made from what the
outputs' tasks recorded, never from what ran this time, so the same inputs give the same bytes
whether a build ran every task, none (up to date) or waited for another build of the folder.

What does change from run to run - the time each task took when it last ran, where this build's
products came from (the cache counters), how long each decomposition took - goes to
``build-stats.json`` in the state folder, which is not for version control.
"""

from __future__ import annotations

import json
from functools import partial
from pathlib import Path
from typing import Any

from mjcfbuild.check.report_page import markdown
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.placing import placed_location, placed_warnings
from mjcfbuild.families import registry
from mjcfbuild.families.decompose import decomposition_summaries
from mjcfbuild.fsutil import write_if_changed
from mjcfbuild.graph.family import read_record
from mjcfbuild.outputs import report_dir

STATS = "build-stats.json"  # in the state folder: what changes from run to run
WARNINGS = "warnings.json"  # in the state folder: each task's warnings when it last ran


def write_stats(ctx: BuildContext) -> Path:
    """Write ``build-stats.json``: every task's seconds when it last ran (this build's merged
    into the stored ones), this build's cache counters (null when no product task ran), each
    decomposition's seconds, and this build's warnings that no task gave (a remote cache out
    of reach, an object it rejected); its path."""
    path = ctx.state(STATS)
    times = read_record(path).get("times") or {}
    times.update({name: round(seconds, 3) for name, seconds in ctx.session.timings.items()})
    stats = {
        "times": dict(sorted(times.items())),
        "cache": ctx.session.cache_report,
        "warnings": build_warnings(ctx),
        "decomposition_seconds": {
            record.stem: summary.get("seconds") for record, summary in decomposition_summaries(ctx)
        },
    }
    write_if_changed(path, (json.dumps(stats, indent=1, sort_keys=True) + "\n").encode())
    ctx.state("timings.json").unlink(missing_ok=True)  # where earlier versions kept the times
    return path


def build_warnings(ctx: BuildContext) -> list[str]:
    """This build's warnings that came from no task (the product sharing's)."""
    given = {w for warnings in ctx.session.task_warnings.values() for w in warnings}
    return [w for w in dict.fromkeys(ctx.session.warnings) if w not in given]


def task_warnings(ctx: BuildContext, tasks: list[str]) -> dict[str, list[str]]:
    """The warnings of each of ``tasks`` that has any, in the order given: this build's for a
    task that ran in it, else those recorded when it last ran."""
    recorded = read_record(ctx.state(WARNINGS))
    recorded.update(ctx.session.task_warnings)
    return {name: list(recorded[name]) for name in tasks if recorded.get(name)}


def record_warnings(ctx: BuildContext, tasks: list[str]) -> None:
    """Keep the warnings of the tasks that ran in this build, by task, beside those of the
    tasks that were up to date; ``tasks`` (every task of the build, in order) decides which
    records stay and their order."""
    kept = task_warnings(ctx, tasks)
    write_if_changed(ctx.state(WARNINGS), (json.dumps(kept, indent=1) + "\n").encode())


def recorded_warnings(ctx: BuildContext) -> list[str]:
    """The warnings of the tasks that made the outputs, in task order, each once, placed
    where the console places them (a xacro source's file and line): what the report lists
    and a no-op prints."""
    recorded = read_record(ctx.state(WARNINGS))
    return placed_warnings(ctx, [w for warnings in recorded.values() for w in warnings])


def write_report(ctx: BuildContext) -> Path:
    """Write report.json and report.md from what the build recorded; the folder they are in."""
    folder = report_dir(ctx)
    folder.mkdir(parents=True, exist_ok=True)
    # Ignored in git by default: the preview pictures are rendered on this machine and its
    # OpenGL (report.md and report.json are the same bytes for the same inputs, and may be
    # added with git add -f).
    _write(
        folder / ".gitignore",
        b"# previews are rendered on this machine; git add -f report.md report.json\n*\n",
    )
    report: dict[str, Any] = {
        "robot": ctx.manifest.name,
        "model": ctx.manifest.robot_file,
        "scene": ctx.manifest.output.scene,
        "warnings": recorded_warnings(ctx),
    }
    for family in registry.FAMILIES:
        if family.report is not None:
            for key, value in family.report(ctx).items():
                given = report.get(key)
                if isinstance(given, dict) and isinstance(value, dict):
                    value = {**given, **value}  # products: a count from each family
                report[key] = value
    _write(folder / "report.json", (json.dumps(report, indent=1, sort_keys=True) + "\n").encode())
    # A check's finding names the link to fix where the warnings name it.
    _write(folder / "report.md", markdown(report, partial(placed_location, ctx)).encode())
    _page_tables(ctx, folder, report)
    ctx.session.written.update(str(folder / n) for n in (".gitignore", "report.json", "report.md"))
    return folder


def _write(path: Path, data: bytes) -> None:
    """Write a file of the report, unless it is one of the user's found in the folder (a
    report.md ``clean`` kept as edited): that stops the build, as a step's write does."""
    import hashlib

    from mjcfbuild.ownership import note_written, refuse_foreign

    refuse_foreign(path, data)
    note_written(path, hashlib.md5(data, usedforsecurity=False).hexdigest())
    write_if_changed(path, data)


def _page_tables(ctx: BuildContext, folder: Path, report: dict) -> None:
    """The report page's tables (output.page), written with the report so that a failed
    check shows there too; without output.page, the page a build left earlier goes."""
    if ctx.manifest.output.page:
        from mjcfbuild.page.tables import tables_script

        (folder / "page").mkdir(exist_ok=True)
        _write(folder / "page" / "tables.js", tables_script(report, partial(placed_location, ctx)))
        ctx.session.written.add(str(folder / "page" / "tables.js"))
        return
    # Only what builds wrote goes (engine.written): a file of the user's stays.
    from mjcfbuild.engine.written import remove_written

    remove_written(ctx, folder / "index.html")
    remove_written(ctx, folder / "page")
