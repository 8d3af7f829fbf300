"""Everything one build of one manifest needs: paths, packages, workers, hashes, errors."""

from __future__ import annotations

import os
import re
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import InternalError, MjcfbuildError
from mjcfbuild.fsutil import normalise

if TYPE_CHECKING:
    from mjcfbuild.engine.hashes import HashCache
    from mjcfbuild.engine.workers import WorkerPool
    from mjcfbuild.manifest.models import Manifest
    from mjcfbuild.sharing.coordinator import ProductSharing
    from mjcfbuild.sharing.settings import SharingChoice
    from mjcfbuild.sources.packages import PackageResolver

STATE_DIR = ".mjcfbuild"
DEFAULT_STEP_TIMEOUT = 1800.0


def default_jobs() -> int:
    """One job per CPU the process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not Linux
        return max(1, os.cpu_count() or 1)


@dataclass
class BuildContext:
    """A validated manifest with its folder, and the state one build of it keeps."""

    manifest: Manifest
    base_dir: Path
    manifest_label: str = "robot.yaml"
    manifest_file: Path | None = None
    jobs: int = field(default_factory=default_jobs)
    environ: dict[str, str] = field(default_factory=lambda: dict(os.environ))
    step_timeout: float | None = DEFAULT_STEP_TIMEOUT
    failures: dict[str, MjcfbuildError] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    notes: dict[str, str] = field(default_factory=dict)
    cache_grew: bool = False
    cache_folder_override: Path | None = None
    output_override: Path | None = None
    prebuilt_mesh_dir: Path | None = None  # convert -a: a folder of meshes converted before
    run_check: bool = True
    noop_stamp: bool = False  # keep a stamp for the no-op fast path (mjcfbuild build)
    use_remote: bool = True
    executor_override: str | None = None
    cache_report: dict | None = None

    def __post_init__(self) -> None:
        self.base_dir = normalise(self.base_dir)
        self._hashes: HashCache | None = None
        self._pool: WorkerPool | None = None
        self._resolver: PackageResolver | None = None
        self._sharing_choice: SharingChoice | None = None
        self._sharing: ProductSharing | None = None
        self._sharing_lock = threading.Lock()  # doit runs tasks in threads

    @classmethod
    def from_manifest_file(cls, path: str | Path, **kwargs) -> BuildContext:
        """Load and validate ``path`` and build a context for it."""
        from mjcfbuild.manifest.loading import load_manifest

        path = Path(path)
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

    @property
    def resolver(self):
        """The :class:`PackageResolver` of this build."""
        if self._resolver is None:
            from mjcfbuild.sources.packages import PackageResolver

            packages = {
                name: self.resolve(folder) for name, folder in self.manifest.packages.items()
            }
            self._resolver = PackageResolver(packages, self.environ)
        return self._resolver

    # Runtime ----------------------------------------------------------------------------

    @property
    def hashes(self):
        """The :class:`HashCache` of this output folder."""
        if self._hashes is None:
            from mjcfbuild.engine.hashes import HashCache

            self._hashes = HashCache(self.state("hashes.json") if self.state_dir.is_dir() else None)
        return self._hashes

    def cache_settings(self) -> dict:
        """The shared product cache as build steps get it: on/off, folder, size cap."""
        from mjcfbuild.engine.store import default_cache_folder, default_max_bytes, parse_size

        settings = self.manifest.cache
        folder = self.resolve(settings.folder) if settings.folder else default_cache_folder()
        if self.cache_folder_override is not None:
            folder = self.cache_folder_override
        max_bytes = parse_size(settings.max_size) if settings.max_size else default_max_bytes()
        return {"enabled": settings.enabled, "folder": str(folder), "max_bytes": max_bytes}

    def sharing_choice(self):
        """The remote cache and executor of this build, checked (:func:`choose`).

        Standard library only: a build with nothing to compute imports no fsspec or dask.
        """
        if self._sharing_choice is None:
            from mjcfbuild.manifest.pinpoint import pinpoint
            from mjcfbuild.sharing.settings import choose

            try:
                self._sharing_choice = choose(
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
        return self._sharing_choice

    @property
    def sharing(self):
        """The :class:`ProductSharing` of this build, made when the first product is needed."""
        with self._sharing_lock:
            if self._sharing is None:
                from mjcfbuild.sharing.coordinator import ProductSharing

                choice = self.sharing_choice()
                self._sharing = ProductSharing(
                    choice.remote,
                    choice.executor,
                    self.warnings.append,
                    self.environ,
                    self.step_timeout,
                )
            return self._sharing

    def finish_sharing(self) -> None:
        """Wait for uploads to the remote cache and keep what was shared for the report."""
        with self._sharing_lock:
            sharing, self._sharing = self._sharing, None
        if sharing is not None:
            self.cache_report = sharing.finish(Path(self.cache_settings()["folder"]))

    def run_step(self, step: str, payload: dict, *, task: str, in_worker: bool) -> dict:
        """Run a build step, in a worker process or here, and return its result.

        Mesh conversions and decompositions go through :class:`ProductSharing` first, which
        may fetch their product from the remote cache or compute it on a cluster.
        """
        from mjcfbuild.sharing.coordinator import SHARED_STEPS

        kind = SHARED_STEPS.get(step)
        if kind is None:
            return self._run_step(step, payload, task, in_worker)
        sharing = self.sharing
        origin = sharing.before(kind, payload, task)
        result = self._run_step(step, payload, task, in_worker)
        sharing.after(kind, payload, origin, result)
        return result

    def _run_step(self, step: str, payload: dict, task: str, in_worker: bool) -> dict:
        if not in_worker:
            import importlib

            module_name, _, function_name = step.partition(":")
            return getattr(importlib.import_module(module_name), function_name)(payload)
        if self._pool is None:
            from mjcfbuild.engine.workers import WorkerPool

            self._pool = WorkerPool(self.jobs, self.base_dir, self.logs_dir)
        self.logs_dir.mkdir(parents=True, exist_ok=True)
        log = self.logs_dir / (re.sub(r"[^A-Za-z0-9_.-]+", "-", task) + ".log")
        return self._pool.run(step, payload, task, log, self.step_timeout)

    def record_failure(self, task: str, error: BaseException) -> MjcfbuildError:
        """Remember why ``task`` failed, as a :class:`MjcfbuildError`."""
        if not isinstance(error, MjcfbuildError):
            import traceback

            error = InternalError(
                f"{task}: {type(error).__name__}: {error}",
                details="".join(traceback.format_exception(error)),
            )
        self.failures[task] = error
        return error

    def close(self) -> None:
        """Stop workers, finish uploads and save the hash cache."""
        self.finish_sharing()
        if self._pool is not None:
            self._pool.close()
            self._pool = None
        if self._hashes is not None:
            if self._hashes.path is None and self.state_dir.is_dir():
                self._hashes.path = self.state("hashes.json")
            self._hashes.save()
