"""Step ``decompose``: convex decomposition of one mesh with CoACD, through the shared cache."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.engine.store import open_store, product_key
from mjcfbuild.engine.versions import step_versions
from mjcfbuild.failpoints import failpoint
from mjcfbuild.steps.outputs import write_output


def run(payload: dict) -> dict:
    """Decompose the collision mesh of a mesh product into ``payload['output_dir']``."""
    mesh_file = collision_mesh(payload)
    output_dir = Path(payload["output_dir"])
    params = payload["params"]
    store = open_store(payload["cache"])
    key = cache_key(payload)
    summary = store.fetch(key, output_dir) if store else None
    cached = summary is not None
    if summary is None:
        from mjcfbuild.collision.decompose import decompose  # coacd: only when needed

        failpoint("decompose")
        summary = decompose(mesh_file, params, output_dir)
        if store:
            store.store(key, output_dir, summary)
    outputs = {str(output_dir / name): digest for name, digest in summary["files"].items()}
    text = json.dumps(summary, indent=1, sort_keys=True) + "\n"
    write_output(Path(payload["summary"]), text.encode(), outputs)
    return {
        "outputs": outputs,
        "cached": cached,
        "stored": not cached and store is not None,
        "note": note(summary),
    }


def note(summary: dict) -> str:
    """What the build prints for a decomposition: parts, concavity reached, seconds."""
    count = len(summary["parts"])
    if summary.get("method") == "hull":
        how = f"hull kept ({summary['hull_concavity']:.3f} <= {summary['hull_tolerance']:g})"
    else:
        how = f"{count} part{'s' if count != 1 else ''}, concavity {summary['concavity']:.3f}"
    return f"{how}, computed in {summary['seconds']:.1f} s"


def collision_mesh(payload: dict) -> Path:
    """The mesh file the decomposition ``payload`` asks for is made from."""
    product = json.loads(Path(payload["product_summary"]).read_text())
    return Path(payload["product_dir"]) / product["collision"]


def cache_key(payload: dict) -> str:
    """The product key of the decomposition ``payload`` asks for (see :func:`product_key`)."""
    params = {**payload["params"], "versions": step_versions("decompose")}
    return product_key("decompose", params, [collision_mesh(payload)])
