"""Step ``mesh``: convert one mesh file into its product (OBJ files and a summary)."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.meshes.convert import convert_mesh
from mjcfbuild.steps.outputs import write_output


def run(payload: dict) -> dict:
    """Convert ``payload['source']`` into ``payload['product_dir']``; write the summary."""
    product_dir = Path(payload["product_dir"])
    summary = convert_mesh(Path(payload["source"]), product_dir, payload["roles"])
    outputs: dict[str, str] = {
        str(product_dir / name): digest for name, digest in summary["files"].items()
    }
    text = json.dumps(summary, indent=1, sort_keys=True) + "\n"
    write_output(Path(payload["summary"]), text.encode(), outputs)
    return {"outputs": outputs}
