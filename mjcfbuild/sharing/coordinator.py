"""Where a product comes from: the local store, the remote cache, the cluster, or here.

:class:`ProductSharing` wraps the two cached steps (mesh conversion and decomposition). Before
the step runs in its local worker, the product is looked up in the local store, then in the
remote cache, then computed on the cluster if there is one; whatever it finds goes into the
local store, where the step then finds it. A product the step computed itself, or the cluster
computed, is uploaded to the remote in the background.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from mjcfbuild.families import decompose, mesh
from mjcfbuild.products.store import ProductStore, open_store
from mjcfbuild.sharing import stats as stats_file
from mjcfbuild.sharing.stats import ShareStats
from mjcfbuild.sharing_settings import ExecutorSpec, RemoteSpec
from mjcfbuild.steps.payloads import DecomposePayload, MeshPayload

# step function -> product kind (the family's name, which sharing.compute's KINDS lists)
SHARED_STEPS = {family.step: family.name for family in (mesh.FAMILY, decompose.FAMILY)}


class ProductSharing:
    """The remote cache and the executor of one build, and what they did."""

    def __init__(
        self,
        remote: RemoteSpec | None,
        executor: ExecutorSpec,
        warn: Callable[[str], None],
        environ: dict[str, str] | None = None,
        step_timeout: float | None = None,
    ) -> None:
        self.stats = ShareStats()
        self.remote_spec = remote
        self.executor_spec = executor
        self._step_timeout = step_timeout
        self._remote = None
        self._executor = None
        if remote is not None:
            from mjcfbuild.sharing.remote import RemoteCache

            self._remote = RemoteCache(remote, self.stats, warn, environ)
        if executor.kind == "dask":
            from mjcfbuild.sharing.dask_executor import DaskExecutor

            self._executor = DaskExecutor(executor, warn)

    def before(self, kind: str, payload: dict, task: str) -> str:
        """Put the product of ``payload`` into the local store if it can be had without
        computing it here; where it came from: local, remote, cluster or here."""
        store = open_store(payload["cache"])
        if store is None or (self._remote is None and self._executor is None):
            return "local-or-here"
        key = _key(kind, payload)
        if store.has(key):
            return "local"
        if self._remote is not None and self._remote.fetch_into(key, store, kind):
            return "remote"
        if self._executor is not None:
            found = self._compute_on_cluster(kind, payload, key, task)
            if found is not None:
                summary, files = found
                _store_files(store, key, summary, files, kind)
                if store.has(key):
                    self.stats.computed(kind, "on_cluster")
                    self._upload(store, key)
                    return "cluster"
        return "here"

    def after(self, kind: str, payload: dict, origin: str, result: dict) -> None:
        """Count what the step did; share a product it computed."""
        self.stats.count("local_dropped", result.get("dropped", 0))
        if result.get("cached"):
            if origin in ("local", "local-or-here"):
                self.stats.count("local_hits")
            return
        self.stats.computed(kind, "here")
        store = open_store(payload["cache"])
        if store is not None and self._remote is not None and result.get("stored"):
            self._upload(store, _key(kind, payload))

    def _upload(self, store: ProductStore, key: str) -> None:
        if self._remote is not None:
            self._remote.upload_later(key, store)

    def _compute_on_cluster(
        self, kind: str, payload: dict, key: str, task: str
    ) -> tuple[dict, dict[str, bytes]] | None:
        assert self._executor is not None
        if kind == "mesh":
            from mjcfbuild.meshes.references import referenced_files
            from mjcfbuild.steps.mesh import check_size, conversion_options

            request = MeshPayload.from_dict(payload)
            if request.looks_from:
                return None  # convert -a borrowing a look: two mesh files, converted here
            main = Path(request.source)
            check_size(main, request.max_file_bytes)
            inputs = [main, *referenced_files(main)]
            options = conversion_options(request)[0]  # the up axis decided here
        else:
            from mjcfbuild.steps.decompose import collision_mesh

            decomposition = DecomposePayload.from_dict(payload)
            main = collision_mesh(decomposition)
            inputs = [main]
            options = decomposition.params
        root = Path(os.path.commonpath([p.parent for p in inputs]))
        files = {path: path.relative_to(root) for path in inputs}
        return self._executor.compute(kind, key, options, files, main, task, self._step_timeout)

    def finish(self, cache_folder: Path | None) -> dict:
        """Wait for uploads, disconnect, record the counters; the report's ``cache`` section."""
        if self._remote is not None:
            self._remote.wait()
        if self._executor is not None:
            self._executor.close()
        data = self.stats.as_dict()
        data["remote"] = self.remote_spec.display if self.remote_spec else None
        data["executor"] = (
            f"dask://{self.executor_spec.address}" if self.executor_spec.kind == "dask" else "local"
        )
        if self.remote_spec is not None and cache_folder is not None:
            stats_file.record(cache_folder, self.remote_spec.display, data)
        return data


def _key(kind: str, payload: dict) -> str:
    from mjcfbuild.steps import decompose, mesh

    if kind == "mesh":
        return mesh.cache_key(MeshPayload.from_dict(payload))
    return decompose.cache_key(DecomposePayload.from_dict(payload))


def _store_files(
    store: ProductStore, key: str, summary: dict, files: dict[str, bytes], kind: str
) -> None:
    import shutil

    temporary = store.temporary_folder(key)
    try:
        temporary.mkdir(parents=True)
        for name, data in files.items():
            (temporary / name).write_bytes(data)
        store.store(key, temporary, summary, kind)
    except OSError:
        pass  # a read-only store: the step computes the product itself
    finally:
        shutil.rmtree(temporary, ignore_errors=True)
