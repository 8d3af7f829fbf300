"""Step ``expand``: the declared source as URDF text, and the files it was made from."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.engine.depfile import Depfile
from mjcfbuild.sources.expand import expand_xacro, read_urdf_file
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.steps.outputs import write_output


def run(payload: dict) -> dict:
    """Expand (xacro) or read (URDF, description) the source into ``payload['output']``."""
    source = Path(payload["source"])
    if payload["kind"] == "xacro":
        packages = PackageResolver(
            {name: Path(folder) for name, folder in payload["packages"].items()},
            payload["environment"],
        )
        expansion = expand_xacro(source, payload["args"], packages)
    else:
        expansion = read_urdf_file(source)
    outputs: dict[str, str] = {}
    write_output(Path(payload["output"]), expansion.urdf, outputs)
    depfile = Path(payload["depfile"])
    Depfile(expansion.files, expansion.missing, expansion.environment).write(depfile)
    return {"outputs": outputs, "discovered": [f for f in expansion.files if f != str(source)]}
