"""Step ``decompose``: convex decomposition of one mesh with CoACD, through the shared cache."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.failpoints import failpoint
from mjcfbuild.meshes.product import read_product
from mjcfbuild.products.store import open_store, product_key
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import DecomposePayload
from mjcfbuild.steps.versions import DECOMPOSE


def run(payload: dict) -> dict:
    """Decompose the collision mesh of a mesh product into ``output_dir``."""
    request = DecomposePayload.from_dict(payload)
    output_dir = Path(request.output_dir)
    if read_product(Path(request.product_summary)).collision is None:
        return _nothing_to_decompose(request)
    mesh_file = collision_mesh(request)
    params = request.params
    store = open_store(request.cache)
    key = cache_key(request)
    summary = store.fetch(key, output_dir, "decompose") if store else None
    cached = summary is not None
    if summary is None:
        from mjcfbuild.collision.decompose import decompose  # coacd: only when needed

        failpoint("decompose")
        summary = decompose(mesh_file, params, output_dir)
        if store:
            store.store(key, output_dir, summary, "decompose")
    outputs = {str(output_dir / name): digest for name, digest in summary["files"].items()}
    text = json.dumps(summary, indent=1, sort_keys=True) + "\n"
    write_output(Path(request.summary), text.encode(), outputs)
    return {
        "outputs": outputs,
        "cached": cached,
        "stored": not cached and store is not None,
        "dropped": len(store.dropped) if store else 0,
        "note": note(summary),
    }


def _nothing_to_decompose(request: DecomposePayload) -> dict:
    """The empty decomposition of a mesh product without a collision mesh: a file that shows
    nothing (a DAE without a scene), whose mesh task said so and whose geoms the model leaves
    out."""
    from mjcfbuild.collision.decompose import DECOMPOSITION_FORMAT

    output_dir = Path(request.output_dir)
    output_dir.mkdir(parents=True, exist_ok=True)
    for stale in output_dir.iterdir():
        stale.unlink()
    summary = {"format": DECOMPOSITION_FORMAT, "parts": [], "files": {}, "method": "none"}
    text = json.dumps(summary, indent=1, sort_keys=True) + "\n"
    write_output(Path(request.summary), text.encode(), {})
    return {"outputs": {}, "cached": False, "stored": False, "dropped": 0, "note": note(summary)}


def note(summary: dict) -> str:
    """What the build prints for a decomposition: parts, concavity reached, seconds."""
    count = len(summary["parts"])
    if summary.get("method") == "none":
        return "nothing to decompose: the mesh shows nothing"
    if summary.get("method") == "hull":
        how = f"hull kept ({summary['hull_concavity']:.3f} <= {summary['hull_tolerance']:g})"
    else:
        how = f"{count} part{'s' if count != 1 else ''}, concavity {summary['concavity']:.3f}"
    return f"{how}, computed in {summary['seconds']:.1f} s"


def collision_mesh(request: DecomposePayload) -> Path:
    """The mesh file the decomposition ``request`` asks for is made from."""
    collision = read_product(Path(request.product_summary)).collision
    assert collision is not None, "a decomposed mesh is collision geometry"
    return Path(request.product_dir) / collision


def cache_key(request: DecomposePayload) -> str:
    """The product key of the decomposition ``request`` asks for (see :func:`product_key`)."""
    params = {**request.params, "versions": DECOMPOSE.versions()}
    return product_key("decompose", params, [collision_mesh(request)])
