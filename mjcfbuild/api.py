"""The Python API: build a manifest from a script or a notebook."""

from __future__ import annotations

import os
from pathlib import Path

from mjcfbuild.engine.context import BuildContext, default_jobs
from mjcfbuild.engine.progress import Progress
from mjcfbuild.engine.runner import BuildResult, run_build
from mjcfbuild.errors import BuildFailed, ManifestError
from mjcfbuild.manifest.models import Manifest


def build(
    manifest: str | os.PathLike | Manifest,
    jobs: int | None = None,
    quiet: bool = True,
    base_dir: str | os.PathLike | None = None,
    check: bool = True,
) -> BuildResult:
    """Build the robot of ``manifest`` (a path to robot.yaml, or a :class:`Manifest`).

    ``jobs`` is the number of tasks run at once (default: ``$MJCFBUILD_JOBS``, else one per
    CPU). With a Manifest object, its relative paths are resolved against ``base_dir``
    (default: the current folder).
    ``check=False`` skips the check against the URDF (as ``build --no-check`` does).
    Returns the :class:`BuildResult`; raises :class:`BuildFailed` listing every error if a
    task failed, and :class:`ManifestError` if the manifest is invalid.
    """
    jobs = jobs or default_jobs()
    cwd = Path.cwd()
    if isinstance(manifest, Manifest):
        ctx = BuildContext(
            manifest, Path(base_dir or cwd), manifest_label="manifest", jobs=jobs, run_check=check
        )
    else:
        path = Path(manifest)
        try:
            ctx = BuildContext.from_manifest_file(path, jobs=jobs, run_check=check)
        except ManifestError as exc:
            raise exc.relocate(path.resolve().parent, cwd) from None
    result = run_build(ctx, Progress(quiet=quiet))
    if not quiet:
        print(result.summary())
    if result.errors:
        raise BuildFailed([error.relocate(ctx.base_dir, cwd) for error in result.errors])
    return result
