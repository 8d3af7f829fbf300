"""Step ``expand``: the declared source as URDF text, and the files it was made from."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.engine.depfile import Depfile
from mjcfbuild.sources.expand import expand_source
from mjcfbuild.steps.outputs import write_output


def run(payload: dict) -> dict:
    """Expand (xacro) or read (URDF, description) the source into ``payload['output']``."""
    source = Path(payload["source"])
    expansion = expand_source(
        source,
        payload["kind"] == "xacro",
        payload["args"],
        payload["packages"],
        payload["environment"],
    )
    outputs: dict[str, str] = {}
    write_output(Path(payload["output"]), expansion.urdf, outputs)
    depfile = Path(payload["depfile"])
    Depfile(expansion.files, expansion.missing, expansion.environment).write(depfile)
    return {"outputs": outputs, "discovered": [f for f in expansion.files if f != str(source)]}
