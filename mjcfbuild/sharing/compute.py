"""Computing a product away from the build's files: what a cluster worker runs.

The build sends the input files' bytes (a mesh and the materials and textures it refers to, or
the collision mesh of a decomposition) with their layout; the worker writes them into a
temporary folder, runs the same conversion or decomposition a local build runs, and sends the
product back as one verified object (:mod:`mjcfbuild.sharing.blob`). Only the standard library
is imported until the work starts, so a worker can answer :func:`worker_versions` cheaply.
"""

from __future__ import annotations

import os
import tempfile
import traceback
from pathlib import Path

KINDS = ("mesh", "decompose")


def worker_versions() -> dict[str, dict[str, str]]:
    """Everything a product depends on besides its inputs, per kind (tool versions, formats)."""
    from mjcfbuild.steps.versions import step_versions

    return {kind: step_versions(kind) for kind in KINDS}


def version_mismatch(expected: dict, found: dict) -> str | None:
    """How ``found`` differs from ``expected`` ('coacd 1.0.5 (the build has 1.0.7)'), if it does."""
    differences = []
    for kind in KINDS:
        for name, version in sorted(expected.get(kind, {}).items()):
            other = found.get(kind, {}).get(name, "missing")
            if other != version:
                item = f"{name} {other} (the build has {version})"
                if item not in differences:
                    differences.append(item)
    return ", ".join(differences) or None


def compute_product(
    kind: str,
    key: str,
    options: dict,
    files: dict[str, bytes],
    main: str,
    expected_versions: dict,
    failpoints: dict[str, str] | None = None,
) -> dict:
    """Compute the product ``key`` from ``files`` (relative name -> bytes; ``main`` is the mesh).

    Returns ``{"object": bytes}``, or ``{"error": ..., "inputs": folder}`` for an error the
    build reports as its own (a refused version, a bad mesh). Never raises for those.
    """
    from mjcfbuild.errors import InternalError, MjcfbuildError
    from mjcfbuild.failpoints import failpoint

    mismatch = version_mismatch(expected_versions, worker_versions())
    if mismatch:
        error = MjcfbuildError(
            f"a Dask worker on {_host()} has {mismatch}; the build refuses its results",
            hint="install the same mjcfbuild, CoACD and trimesh versions on every worker",
        )
        return {"error": error.to_dict(), "refused": True}
    with tempfile.TemporaryDirectory(prefix="mjcfbuild-cluster-") as folder:
        inputs, output = Path(folder) / "in", Path(folder) / "out"
        try:
            failpoint(f"cluster-{kind}", **(failpoints or {}))
            for name, data in files.items():
                path = inputs / name
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_bytes(data)
            summary = _run(kind, options, inputs / main, output)
            from mjcfbuild.sharing.blob import pack

            return {"object": pack(key, output, summary)}
        except MjcfbuildError as exc:
            return {"error": exc.to_dict(), "inputs": str(inputs)}
        except Exception as exc:
            error = InternalError(f"{type(exc).__name__}: {exc}")
            return {"error": error.to_dict(), "traceback": traceback.format_exc()}


def _run(kind: str, options: dict, source: Path, output: Path) -> dict:
    if kind == "mesh":
        from mjcfbuild.meshes.convert import convert_with_options

        return convert_with_options(source, output, options).to_dict()
    from mjcfbuild.collision.decompose import decompose

    return decompose(source, options, output)


def _host() -> str:
    return os.uname().nodename if hasattr(os, "uname") else "a worker"
