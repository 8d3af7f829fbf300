"""The ``package`` family: a Menagerie-grade folder of the model (``output.package``)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.graph.family import Family, file_task
from mjcfbuild.outputs import (
    ASSEMBLY_REPORT,
    CHECK_RESULTS,
    PACKAGE_FOLDER,
    PACKAGE_RECORD,
    report_dir,
)
from mjcfbuild.steps.payloads import PackagePayload
from mjcfbuild.steps.versions import tool_version

if TYPE_CHECKING:
    from mjcfbuild.graph.context import GraphContext
    from mjcfbuild.graph.graph import Graph


def _tasks(graph: Graph) -> list[dict]:
    from mjcfbuild.package.documents import git_revision, search_license

    ctx, prefix, checked = graph.ctx, graph.prefix, graph.checks
    if not ctx.manifest.output.package:
        return []
    folder = ctx.out_dir / PACKAGE_FOLDER
    revision, remote = git_revision(ctx.base_dir)
    top = _git_top(ctx.base_dir) if revision else None
    package_folders = [ctx.resolve(path) for path in ctx.manifest.packages.values()]
    license_file, looked = search_license(
        [ctx.source_base_dir, *package_folders, ctx.base_dir], top
    )
    picture = report_dir(ctx) / "previews" / "three_quarter_visual.png"
    with_picture = checked and ctx.manifest.check.previews
    payload = PackagePayload(
        name=ctx.manifest.name,
        provenance={
            "source": ctx.portable_label(ctx.source_path),
            "manifest_text": ctx.manifest_file.read_text() if ctx.manifest_file else "",
            "mujoco_version": tool_version("mujoco"),
            "license_from": _license_label(ctx, license_file),
        },
        git={"revision": revision, "remote": remote},
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
    task = file_task(
        ctx,
        FAMILY,
        f"{prefix}package",
        f"package {PACKAGE_FOLDER}/",
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
        absent=looked,  # a LICENSE added there later is the package's
    )
    return [task]


def _license_label(ctx: GraphContext, license_file: Path | None) -> str:
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


FAMILY = Family(
    name="package",
    step="mjcfbuild.steps.package:run",
    payload=PackagePayload,
    # 2: <dcmotor> gains rounded and shared in classes; 3: no stale picture; 4: the README's git
    # revision as of the package's last change, no parameter of the task
    format=4,
    tools=("mujoco", "numpy", "lxml"),
    tasks=_tasks,
)
