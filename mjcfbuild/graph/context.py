"""The configuration of one build of one manifest: its manifest, folders, paths and options.

The engine's :class:`mjcfbuild.engine.context.BuildContext` adds the session a build runs in;
the task families and the graph's helpers see that session as the :class:`Session` protocol
here, so nothing below the engine imports it."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, Self

from mjcfbuild.errors import MjcfbuildError
from mjcfbuild.filesig import file_clock_ns
from mjcfbuild.fsutil import normalise
from mjcfbuild.jobs import default_jobs
from mjcfbuild.ownership import STATE_DIR

if TYPE_CHECKING:
    from mjcfbuild.errors import MjcfbuildError as StepError
    from mjcfbuild.graph.hashes import HashCache
    from mjcfbuild.manifest.models import Manifest
    from mjcfbuild.sharing_settings import SharingChoice
    from mjcfbuild.sources.packages import PackageResolver

DEFAULT_STEP_TIMEOUT = 1800.0


class Session(Protocol):
    """What the graph's tasks use of the build that runs them (the engine's BuildSession)."""

    warnings: list[str]
    task_warnings: dict[str, list[str]]
    timings: dict[str, float]
    notes: dict[str, str]
    written: set[str]
    cache_grew: bool

    @property
    def hashes(self) -> HashCache:
        """The build's cache of file hashes."""
        ...

    def run_step(self, step: str, payload: dict, *, task: str, in_worker: bool) -> dict:
        """Run ``step`` on ``payload`` for ``task``; its result."""
        ...

    def record_failure(self, task: str, error: BaseException) -> StepError:
        """Keep ``task``'s failure for the report; the error to show."""
        ...


@dataclass(frozen=True)
class GraphContext:
    """A validated manifest with its folder and the options of a build: the configuration,
    which does not change while the build runs. What does change is in :attr:`session`, which
    the engine's BuildContext (the class to construct) starts."""

    manifest: Manifest
    base_dir: Path
    manifest_label: str = "robot.yaml"
    manifest_file: Path | None = None
    jobs: int = field(default_factory=default_jobs)
    environ: dict[str, str] = field(default_factory=lambda: dict(os.environ))
    step_timeout: float | None = DEFAULT_STEP_TIMEOUT
    cache_folder_override: Path | None = None
    output_override: Path | None = None
    prebuilt_mesh_dir: Path | None = None  # convert -a: a folder of meshes converted before
    run_check: bool = True
    noop_stamp: bool = False  # keep a stamp for the no-op fast path (mjcfbuild build)
    command_stamp_key: str | None = None  # the stamp's key without a manifest file (convert)
    use_remote: bool = True
    executor_override: str | None = None
    allow_outside: bool = False  # --allow-outside: output.folder may leave the manifest's tree
    # When the build began reading its inputs (filesig.file_clock_ns()): a stamp never
    # vouches for an input changed since (mjcfbuild.engine.stamp).
    started_ns: int = field(default_factory=file_clock_ns)
    session: Session = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        # Frozen: the field set here is set once, as the dataclass itself would.
        object.__setattr__(self, "base_dir", normalise(self.base_dir))

    @classmethod
    def from_manifest_file(cls, path: str | Path, **kwargs: Any) -> Self:
        """Load and validate ``path`` and build a context for it."""
        from mjcfbuild.manifest.loading import load_manifest

        path = Path(path)
        kwargs.setdefault("started_ns", file_clock_ns())
        manifest = load_manifest(path)
        ctx = cls(
            manifest,
            normalise(path).parent,
            manifest_label=str(path),
            manifest_file=normalise(path),
            **kwargs,
        )
        ctx.check_package_folders()
        return ctx

    def check_package_folders(self) -> None:
        """Refuse a ``packages`` entry whose folder does not exist: it is always a typo, and
        would otherwise surface later as a confusing missing mesh."""
        from mjcfbuild.errors import ManifestError
        from mjcfbuild.manifest.pinpoint import pinpoint

        for name, folder in sorted(self.manifest.packages.items()):
            if self.resolve(folder).is_dir():
                continue
            error = ManifestError(
                f"package '{name}' points at '{folder}', which is not a folder",
                file=f"{self.manifest_label} packages.{name}",
                hint="fix the folder (relative to robot.yaml) or remove the entry",
            )
            if self.manifest_file is not None:
                pinpoint(error, self.manifest_label, self.manifest_file)
            raise error

    @property
    def stamp_key(self) -> Path | str | None:
        """What the no-op stamp of this build is filed under: the command line's key
        (``convert``), else the manifest file; None when neither exists."""
        return self.command_stamp_key or self.manifest_file

    # Paths ------------------------------------------------------------------------------

    def resolve(self, relative: str) -> Path:
        """A manifest path, made absolute against the manifest's folder."""
        return normalise(self.base_dir / os.path.expanduser(relative))

    def label(self, path: str | Path) -> str:
        """How messages show ``path``: relative to the manifest's folder when inside it."""
        path = Path(path)
        try:
            return str(path.relative_to(self.base_dir))
        except ValueError:
            return str(path)

    def portable_label(self, path: str | Path) -> str:
        """``path`` relative to the manifest's folder even when outside it (``../x.urdf``), with
        forward slashes: the same text whichever folder the build runs in, for outputs."""
        return Path(os.path.relpath(Path(path), self.base_dir)).as_posix()

    @property
    def manifest_output_label(self) -> str:
        """How what a step writes (warnings, origins) names the manifest: relative to its own
        folder (``robot.yaml``), so that reports are the same bytes whichever folder and
        current directory the build runs in; the console label without a manifest file."""
        if self.manifest_file is None:
            return self.manifest_label
        return self.portable_label(self.manifest_file)

    @property
    def out_dir(self) -> Path:
        """The output folder."""
        if self.output_override is not None:
            return self.output_override
        return self.resolve(self.manifest.output.folder)

    @property
    def state_dir(self) -> Path:
        """Where the build keeps its database and intermediate files."""
        return self.out_dir / STATE_DIR

    @property
    def robot_path(self) -> Path:
        """The robot model file."""
        return self.out_dir / self.manifest.robot_file

    @property
    def scene_path(self) -> Path:
        """The scene file."""
        return self.out_dir / self.manifest.output.scene

    @property
    def urdf_path(self) -> Path | None:
        """The exported URDF, if the manifest asks for one."""
        export = self.manifest.output.urdf
        assert not isinstance(export, str), "validation makes a file name a UrdfExport"
        return self.out_dir / export.file if export else None

    @property
    def urdf_mesh_dir(self) -> Path | None:
        """The folder of the exported URDF's meshes, if the manifest asks for a URDF."""
        export = self.manifest.output.urdf
        assert not isinstance(export, str), "validation makes a file name a UrdfExport"
        return self.out_dir / export.mesh_folder if export else None

    @property
    def assets_dir(self) -> Path:
        """Where mesh and texture files of the model go."""
        return self.out_dir / "assets"

    def state(self, name: str) -> Path:
        """A file in the state folder."""
        return self.state_dir / name

    @property
    def products_dir(self) -> Path:
        """Converted meshes, one folder per mesh."""
        return self.state_dir / "products"

    @property
    def logs_dir(self) -> Path:
        """What build steps printed, one file per task."""
        return self.state_dir / "logs"

    # Sources ----------------------------------------------------------------------------

    @property
    def source_kind(self) -> str:
        """``urdf``, ``xacro`` or ``description``."""
        source = self.manifest.source
        return "xacro" if source.xacro else "urdf" if source.urdf else "description"

    @property
    def source_path(self) -> Path:
        """The file the robot description is read from (stdin is kept in the state folder)."""
        source = self.manifest.source
        if source.description == "-":
            return self.state("stdin.urdf")
        path = source.xacro or source.urdf or source.description
        assert path is not None, "validation requires one of the three"
        return self.resolve(path)

    @property
    def source_base_dir(self) -> Path:
        """Relative mesh paths are relative to the URDF/xacro file's folder, or for a
        description (which may come from a string or stdin) to the manifest's folder."""
        if self.source_kind == "description":
            return self.base_dir
        return self.source_path.parent

    @cached_property
    def resolver(self) -> PackageResolver:
        """The :class:`PackageResolver` of this build."""
        from mjcfbuild.sources.packages import PackageResolver

        packages = {name: self.resolve(folder) for name, folder in self.manifest.packages.items()}
        return PackageResolver(packages, self.environ)

    # Services ---------------------------------------------------------------------------

    def cache_settings(self) -> dict:
        """The shared product cache as build steps get it: on/off, folder, size cap."""
        from mjcfbuild.products.store import default_cache_folder, default_max_bytes, parse_size

        settings = self.manifest.cache
        folder = self.resolve(settings.folder) if settings.folder else default_cache_folder()
        if self.cache_folder_override is not None:
            folder = self.cache_folder_override
        max_bytes = parse_size(settings.max_size) if settings.max_size else default_max_bytes()
        return {"enabled": settings.enabled, "folder": str(folder), "max_bytes": max_bytes}

    @cached_property
    def sharing_choice(self) -> SharingChoice:
        """The remote cache and executor of this build, checked (:func:`choose`).

        Standard library only: a build with nothing to compute imports no fsspec or dask.
        """
        from mjcfbuild.manifest.pinpoint import pinpoint
        from mjcfbuild.sharing_settings import choose

        try:
            return choose(
                manifest_remote=getattr(self.manifest.cache, "remote", None),
                manifest_executor=getattr(self.manifest, "executor", None),
                environ=self.environ,
                cli_executor=self.executor_override,
                use_remote=self.use_remote and self.manifest.cache.enabled,
                manifest_label=self.manifest_label,
            )
        except MjcfbuildError as error:
            if self.manifest_file is not None:
                pinpoint(error, self.manifest_label, self.manifest_file)
            raise
