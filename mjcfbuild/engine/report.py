"""The build report: ``report/report.json`` and ``report/report.md`` in the output folder.

This module gathers what the build steps recorded - the check results, inertia repairs,
warnings, mesh statistics, the time each task took when it last ran, and the preview pictures -
into one machine-readable file; :mod:`mjcfbuild.check.report_page` renders the page people
read. The report describes the last build on this machine (its times differ from run to run),
so its folder ignores itself in git.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from mjcfbuild.check.report_page import markdown
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.tasks import (
    ASSEMBLY_REPORT,
    CHECK_RESULTS,
    TRAINING_RECORD,
    TUNING_RECORD,
    decomposition_dir,
    report_dir,
    training_paths,
)
from mjcfbuild.fsutil import md5_file, write_if_changed

TIMINGS = "timings.json"
TASK_WARNINGS = "warnings.json"
PREVIEW_ORDER = (
    "three_quarter_visual",
    "side_visual",
    "top_visual",
    "closeup_visual",
    "three_quarter_collision",
    "side_collision",
    "closeup_collision",
)


def record_timings(ctx: BuildContext) -> dict[str, float]:
    """Merge this build's task times into the stored ones; all of them."""
    path = ctx.state(TIMINGS)
    try:
        timings = json.loads(path.read_text())
    except (OSError, ValueError):
        timings = {}
    timings.update({name: round(seconds, 3) for name, seconds in ctx.session.timings.items()})
    write_if_changed(path, (json.dumps(dict(sorted(timings.items())), indent=1) + "\n").encode())
    return timings


def record_warnings(ctx: BuildContext, task_names: list[str]) -> list[str]:
    """Merge the warnings of the tasks this build ran into those stored from earlier builds,
    for the tasks still in the graph (``task_names``); every current warning, in graph order,
    then this build's warnings no task gave (the remote cache's).

    A task that is up to date gives no warnings, yet what it warned about when it ran is
    still true of the model: the report keeps saying so."""
    path = ctx.state(TASK_WARNINGS)
    try:
        stored = json.loads(path.read_text())
    except (OSError, ValueError):
        stored = {}
    stored.update(ctx.session.task_warnings)
    kept = {name: stored[name] for name in task_names if stored.get(name)}
    write_if_changed(path, (json.dumps(kept, indent=1, sort_keys=True) + "\n").encode())
    from_tasks = [warning for name in task_names for warning in kept.get(name, [])]
    return list(dict.fromkeys([*from_tasks, *ctx.session.warnings]))


def write_report(ctx: BuildContext, warnings: list[str]) -> Path:
    """Write report.json and report.md; the folder they are in."""
    folder = report_dir(ctx)
    folder.mkdir(parents=True, exist_ok=True)
    write_if_changed(folder / ".gitignore", b"# the report of the last build on this machine\n*\n")
    check = _read(ctx.state(CHECK_RESULTS))
    assembly = _read(ctx.state(ASSEMBLY_REPORT))
    previews = sorted(
        (p.name for p in (folder / "previews").glob("*.png")),
        key=lambda n: PREVIEW_ORDER.index(n[:-4]) if n[:-4] in PREVIEW_ORDER else 99,
    )
    report = {
        "robot": ctx.manifest.name,
        "model": ctx.manifest.robot_file,
        "scene": ctx.manifest.output.scene,
        "check": check,
        "repairs": assembly.get("repairs", []),
        "warnings": warnings,
        "bodies": assembly.get("bodies"),
        "geoms": assembly.get("geoms"),
        "assets": assembly.get("assets", []),
        "readiness": assembly.get("readiness") or {},
        "self_collision": assembly.get("self_collision"),
        "decompositions": decompositions(ctx),
        "up_axis": up_axis_decisions(ctx),
        "times": record_timings(ctx),
        "cache": ctx.session.cache_report,
        "previews": [f"previews/{name}" for name in previews],
        "tuning": _read(ctx.state(TUNING_RECORD)) if ctx.manifest.check.tuning else {},
        "training": training_summary(ctx),
    }
    write_if_changed(
        folder / "report.json", (json.dumps(report, indent=1, sort_keys=True) + "\n").encode()
    )
    write_if_changed(folder / "report.md", markdown(report).encode())
    _page_tables(ctx, folder, report)
    return folder


def _page_tables(ctx: BuildContext, folder: Path, report: dict) -> None:
    """The report page's tables (output.page), written with the report so that a failed
    check shows there too; without output.page, the page a build left earlier goes."""
    if ctx.manifest.output.page:
        from mjcfbuild.page.tables import tables_script

        (folder / "page").mkdir(exist_ok=True)
        write_if_changed(folder / "page" / "tables.js", tables_script(report))
        return
    (folder / "index.html").unlink(missing_ok=True)
    if (folder / "page").is_dir():
        shutil.rmtree(folder / "page")


def decompositions(ctx: BuildContext) -> list[dict]:
    """Per decomposition of this build: hull kept or CoACD, parts, concavities, seconds."""
    rows = []
    for path in sorted(decomposition_dir(ctx, "any").parent.glob("*.json")):
        summary = _read(path)
        if "parts" not in summary:
            continue
        rows.append(
            {
                "name": path.stem,
                "method": summary.get("method", "coacd"),
                "parts": len(summary["parts"]),
                "hull_concavity": summary.get("hull_concavity"),
                "concavity": summary.get("concavity"),
                "seconds": summary.get("seconds"),
            }
        )
    return rows


def up_axis_decisions(ctx: BuildContext) -> list[dict]:
    """Per DAE file tagged other than Z-up: its mesh, whether it was turned, and why."""
    rows = []
    for path in sorted(ctx.products_dir.glob("*.json")):
        decision = _read(path).get("up_axis")
        if isinstance(decision, dict):
            rows.append({"mesh": path.stem, **decision})
    return rows


TRAINING_WARP = "training_warp.json"  # what check --warp measured of the variant


def training_summary(ctx: BuildContext) -> dict | None:
    """The training variant's record, with what ``check --warp`` measured of it while the
    variant is the one it measured (by content)."""
    if ctx.manifest.training is None:
        return None
    record = _read(ctx.state(TRAINING_RECORD))
    if not record:
        return None
    variant, _ = training_paths(ctx)
    warp = _read(ctx.state(TRAINING_WARP))
    try:
        current = md5_file(variant)
    except OSError:
        current = None
    return {
        **record,
        "file": variant.name,
        "warp": warp if warp and warp.get("variant_md5") == current else None,
    }


def _read(path: Path) -> dict:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return {}
