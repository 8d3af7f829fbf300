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
    product = json.loads(Path(payload["product_summary"]).read_text())
    mesh_file = Path(payload["product_dir"]) / product["collision"]
    output_dir = Path(payload["output_dir"])
    params = payload["params"]
    store = open_store(payload["cache"])
    key = product_key("decompose", {**params, "versions": step_versions("decompose")}, [mesh_file])
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
    return {"outputs": outputs, "cached": cached, "stored": not cached and store is not None}
