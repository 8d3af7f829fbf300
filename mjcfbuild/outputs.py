"""The names of the files a build writes, and where each one lies in the output folder.

One module for every name, so that the task that writes a file and the code that reads it
(the next task, the report, ``check``, ``clean``) cannot disagree. Names without a folder are
in the state folder (``ctx.state(NAME)``, ``.mjcfbuild/``). Standard library only: the task
declarations import it on every build.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from mjcfbuild.manifest.models import Manifest

SOURCE_URDF = "source.urdf"
SOURCE_DEPS = "source.deps.json"
COMPOSED_URDF = "composed.urdf"
PARTS_DIR = "attach"  # the attach: parts' expanded URDFs and normalised MJCF
PLAN = "plan.json"
REFERENCE = "reference.json"  # what the check's independent reader read from the URDF
SRDF_SUMMARY = "srdf.json"
SELF_COLLISION = "self_collision.json"
ASSEMBLY_REPORT = "assembly.json"
# The lowest collision point at home, apart from the assembly report, so the scene's floor
# follows it without rerunning for every other change of the model.
FLOOR_RECORD = "floor.json"
URDF_EXPORT_RECORD = "urdf_export.json"
TRAINING_RECORD = "training.json"
TRAINING_WARP = "training_warp.json"  # what check --warp measured of the variant
CHECK_RESULTS = "check.json"
PREVIEWS_RECORD = "previews.json"
TUNING_RECORD = "tuning.json"
PACKAGE_RECORD = "package.json"
PACKAGE_FOLDER = "package"  # the Menagerie-grade folder, inside the output folder
# The report page's files, inside the report folder (mjcfbuild.steps.page writes them).
PAGE_FILES = (
    "index.html",
    "page/mujoco.js",
    "page/mujoco-wasm.js",
    "page/model.js",
    "page/viewer.js",
    "page/page.css",
)


class Folders(Protocol):
    """Where a build writes (mjcfbuild.graph.context.Folders): outputs.py sits below it."""

    @property
    def manifest(self) -> Manifest: ...
    @property
    def out_dir(self) -> Path: ...
    @property
    def state_dir(self) -> Path: ...
    @property
    def products_dir(self) -> Path: ...
    def state(self, name: str) -> Path: ...


def report_dir(ctx: Folders) -> Path:
    """Where the human report, report.json and the previews go."""
    return ctx.out_dir / "report"


def product_summary(ctx: Folders, mesh_id: str) -> Path:
    """Where the summary of a mesh's product is written."""
    return ctx.products_dir / f"{mesh_id}.json"


def mesh_depfile(ctx: Folders, mesh_id: str) -> Path:
    """The files a mesh's conversion read besides the mesh (a DAE's textures, an OBJ's MTL)."""
    return ctx.products_dir / f"{mesh_id}.deps.json"


def decomposition_dir(ctx: Folders, name: str) -> Path:
    """Where the parts of a decomposition are written."""
    return ctx.state_dir / "decompositions" / name


def training_paths(ctx: Folders) -> tuple[Path, Path]:
    """The training variant's file and its scene's."""
    files = ctx.manifest.training_files
    assert files is not None, "asked only when robot.yaml sets output.training"
    return ctx.out_dir / files[0], ctx.out_dir / files[1]


def part_urdf(ctx: Folders, index: int) -> Path:
    """Where the expanded URDF of ``attach:`` part ``index`` is kept."""
    return ctx.state_dir / PARTS_DIR / f"{index}.urdf"


def mjcf_part_paths(ctx: Folders, index: int) -> dict[str, Path]:
    """Where the ``part:`` task of MJCF part ``index`` writes its normalised XML, summary,
    depfile and (shared by every part, content-addressed) asset copies."""
    folder = ctx.state_dir / PARTS_DIR
    return {
        "xml": folder / f"{index}.mjcf.xml",
        "summary": folder / f"{index}.mjcf.json",
        "depfile": folder / f"{index}.mjcf.deps.json",
        "assets_dir": folder / "assets",
    }


def has_urdf_parts(manifest: Manifest) -> bool:
    """Whether URDF or xacro parts are joined to the main source (into composed.urdf)."""
    return any(part.source.kind != "mjcf" for part in manifest.attach)


def planned_urdf(ctx: Folders) -> Path:
    """The URDF the plan reads and the check compares with: the expanded source, or with
    ``attach:`` parts, the source with the parts joined to it."""
    return ctx.state(COMPOSED_URDF) if has_urdf_parts(ctx.manifest) else ctx.state(SOURCE_URDF)
