"""The build report: ``report/report.json`` and ``report/report.md`` in the output folder.

This module gathers what the build steps recorded - the check results, inertia repairs,
the warnings of the tasks that made the outputs, mesh statistics, the products and the preview
pictures - into one machine-readable file; :mod:`mjcfbuild.check.report_page` renders the page
people read. Both are made from what the outputs' tasks recorded, never from what ran this
time, so the same inputs give the same bytes whether a build ran every task, none (up to date)
or waited for another build of the folder.

What does change from run to run - the time each task took when it last ran, where this build's
products came from (the cache counters), how long each decomposition took - goes to
``build-stats.json`` in the state folder, which is not for version control.
"""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.check.report_page import markdown
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.fsutil import md5_file, write_if_changed
from mjcfbuild.outputs import (
    ASSEMBLY_REPORT,
    CHECK_RESULTS,
    TRAINING_RECORD,
    TUNING_RECORD,
    decomposition_dir,
    report_dir,
    training_paths,
)

STATS = "build-stats.json"  # in the state folder: what changes from run to run
WARNINGS = "warnings.json"  # in the state folder: each task's warnings when it last ran
PREVIEW_ORDER = (
    "three_quarter_visual",
    "side_visual",
    "top_visual",
    "closeup_visual",
    "three_quarter_collision",
    "side_collision",
    "closeup_collision",
)


def write_stats(ctx: BuildContext) -> Path:
    """Write ``build-stats.json``: every task's seconds when it last ran (this build's merged
    into the stored ones), this build's cache counters (null when no product task ran), each
    decomposition's seconds, and this build's warnings that no task gave (a remote cache out
    of reach, an object it rejected); its path."""
    path = ctx.state(STATS)
    times = _read(path).get("times") or {}
    times.update({name: round(seconds, 3) for name, seconds in ctx.session.timings.items()})
    stats = {
        "times": dict(sorted(times.items())),
        "cache": ctx.session.cache_report,
        "warnings": _build_warnings(ctx),
        "decomposition_seconds": {
            record.stem: summary.get("seconds") for record, summary in _decomposition_summaries(ctx)
        },
    }
    write_if_changed(path, (json.dumps(stats, indent=1, sort_keys=True) + "\n").encode())
    ctx.state("timings.json").unlink(missing_ok=True)  # where earlier versions kept the times
    return path


def _build_warnings(ctx: BuildContext) -> list[str]:
    """This build's warnings that came from no task (the product sharing's)."""
    given = {w for warnings in ctx.session.task_warnings.values() for w in warnings}
    return [w for w in dict.fromkeys(ctx.session.warnings) if w not in given]


def record_warnings(ctx: BuildContext, tasks: list[str]) -> None:
    """Keep the warnings of the tasks that ran in this build, by task, beside those of the
    tasks that were up to date; ``tasks`` (every task of the build, in order) decides which
    records stay and their order."""
    recorded = _read(ctx.state(WARNINGS))
    recorded.update(ctx.session.task_warnings)
    kept = {name: list(recorded[name]) for name in tasks if recorded.get(name)}
    write_if_changed(ctx.state(WARNINGS), (json.dumps(kept, indent=1) + "\n").encode())


def recorded_warnings(ctx: BuildContext) -> list[str]:
    """The warnings of the tasks that made the outputs, in task order, each once."""
    recorded = _read(ctx.state(WARNINGS))
    return list(dict.fromkeys(w for warnings in recorded.values() for w in warnings))


def write_report(ctx: BuildContext) -> Path:
    """Write report.json and report.md from what the build recorded; the folder they are in."""
    folder = report_dir(ctx)
    folder.mkdir(parents=True, exist_ok=True)
    # Ignored in git by default: the preview pictures are rendered on this machine and its
    # OpenGL (report.md and report.json are the same bytes for the same inputs, and may be
    # added with git add -f).
    write_if_changed(
        folder / ".gitignore",
        b"# previews are rendered on this machine; git add -f report.md report.json\n*\n",
    )
    check = _read(ctx.state(CHECK_RESULTS))
    assembly = _read(ctx.state(ASSEMBLY_REPORT))
    previews = sorted(
        (p.name for p in (folder / "previews").glob("*.png")),
        key=lambda n: PREVIEW_ORDER.index(n[:-4]) if n[:-4] in PREVIEW_ORDER else 99,
    )
    decomposed = decompositions(ctx)
    report = {
        "robot": ctx.manifest.name,
        "model": ctx.manifest.robot_file,
        "scene": ctx.manifest.output.scene,
        "check": check,
        "repairs": assembly.get("repairs", []),
        "warnings": recorded_warnings(ctx),
        "bodies": assembly.get("bodies"),
        "geoms": assembly.get("geoms"),
        "assets": assembly.get("assets", []),
        "readiness": assembly.get("readiness") or {},
        "self_collision": assembly.get("self_collision"),
        "decompositions": decomposed,
        "up_axis": up_axis_decisions(ctx),
        "products": {
            "meshes": len(mesh_products(ctx)),
            "decompositions": len(decomposed),
        },
        "previews": [f"previews/{name}" for name in previews],
        "tuning": _read(ctx.state(TUNING_RECORD)) if ctx.manifest.check.tuning else {},
        "training": training_summary(ctx),
    }
    write_if_changed(
        folder / "report.json", (json.dumps(report, indent=1, sort_keys=True) + "\n").encode()
    )
    write_if_changed(folder / "report.md", markdown(report).encode())
    _page_tables(ctx, folder, report)
    ctx.session.written.update(str(folder / n) for n in (".gitignore", "report.json", "report.md"))
    return folder


def _page_tables(ctx: BuildContext, folder: Path, report: dict) -> None:
    """The report page's tables (output.page), written with the report so that a failed
    check shows there too; without output.page, the page a build left earlier goes."""
    if ctx.manifest.output.page:
        from mjcfbuild.page.tables import tables_script

        (folder / "page").mkdir(exist_ok=True)
        write_if_changed(folder / "page" / "tables.js", tables_script(report))
        ctx.session.written.add(str(folder / "page" / "tables.js"))
        return
    # Only what builds wrote goes (engine.written): a file of the user's stays.
    from mjcfbuild.engine.written import remove_written

    remove_written(ctx, folder / "index.html")
    remove_written(ctx, folder / "page")


def decompositions(ctx: BuildContext) -> list[dict]:
    """Per decomposition of this build: hull kept or CoACD, parts, concavities (its seconds
    are in build-stats.json)."""
    return [
        {
            "name": path.stem,
            "method": summary.get("method", "coacd"),
            "parts": len(summary["parts"]),
            "hull_concavity": summary.get("hull_concavity"),
            "concavity": summary.get("concavity"),
        }
        for path, summary in _decomposition_summaries(ctx)
    ]


def _decomposition_summaries(ctx: BuildContext) -> list[tuple[Path, dict]]:
    """Each decomposition's record, by name."""
    found = []
    for path in sorted(decomposition_dir(ctx, "any").parent.glob("*.json")):
        summary = _read(path)
        if "parts" in summary:
            found.append((path, summary))
    return found


def mesh_products(ctx: BuildContext) -> list[Path]:
    """The records of the mesh products of this build (``products/<id>.json`` beside the
    product's folder)."""
    return [p for p in sorted(ctx.products_dir.glob("*.json")) if (p.parent / p.stem).is_dir()]


def up_axis_decisions(ctx: BuildContext) -> list[dict]:
    """Per DAE file tagged other than Z-up: its mesh, whether it was turned, and why."""
    rows = []
    for path in mesh_products(ctx):
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
