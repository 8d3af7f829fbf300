"""The training variant's files, removed when robot.yaml no longer asks for them; and the
model and scene of an earlier name.

The ``training`` task records the files it wrote (``.mjcfbuild/training.json``). Before a
build's tasks run, the recorded files that this build will not write are removed from the
output folder: all of them, with the record and what ``check --warp`` measured, when
``output.training`` is off; the old names when ``file`` or ``scene`` changed. Only files the
record names are touched, so a user's own file of the same name in another build's folder
is never at risk.
"""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.outputs import TRAINING_RECORD, TRAINING_WARP, training_paths


def remove_stale_variant(ctx: BuildContext) -> list[Path]:
    """Remove the variant files an earlier build wrote that this one will not; the paths
    removed."""
    record = ctx.state(TRAINING_RECORD)
    if not record.exists():
        return []
    try:
        files = json.loads(record.read_text()).get("files", [])
    except (OSError, ValueError):
        files = []
    keep = set(training_paths(ctx)) if ctx.manifest.training else set()
    removed = []
    for name in files:
        path = ctx.out_dir / Path(name).name  # names in the output folder, nothing above it
        if path not in keep and path.is_file():
            path.unlink()
            removed.append(path)
    if not ctx.manifest.training:
        record.unlink()
        ctx.state(TRAINING_WARP).unlink(missing_ok=True)
    return removed


def remove_renamed_model(ctx: BuildContext) -> tuple[list[Path], list[Path]]:
    """Remove the model and scene files an earlier build wrote under names this one will not
    write (robot.yaml's ``name:``, ``output.robot`` or ``output.scene`` changed): the MJCF
    files at the top of the output folder the record of written files names, that still hold
    what the build wrote (one the user edited stays, as ``clean`` keeps it); the paths
    removed, and those kept as edited. A rename left the old model beside the new one,
    looking current. Called once the build wrote the model under its new name: a failed
    build leaves the old one."""
    from mjcfbuild.engine import written

    recorded = written.recorded(ctx) or {}
    keep = {ctx.robot_path, ctx.scene_path}
    keep |= set(training_paths(ctx)) if ctx.manifest.training else set()
    removed, kept = [], []
    for name, digest in recorded.items():
        path = ctx.out_dir / name
        if "/" in name or not name.endswith(".xml") or path in keep or digest is None:
            continue
        if not written.written_file(ctx.out_dir, name):
            continue
        if written.edited(ctx.out_dir, name, digest):
            kept.append(path)
        else:
            path.unlink()
            removed.append(path)
    return removed, kept
