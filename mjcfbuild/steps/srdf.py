"""Step ``srdf``: read the SRDF named by ``self_collision.srdf`` (expanding it if it is xacro)."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.selfcollision.srdf import parse_srdf
from mjcfbuild.sources.expand import expand_source
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import SrdfPayload


def run(payload: dict) -> dict:
    """Write the SRDF's disabled pairs and group states to its ``output``."""
    request = SrdfPayload.from_dict(payload)
    source = Path(request.source)
    expansion = expand_source(
        source,
        source.name.endswith(".xacro"),
        request.args,
        request.packages,
        request.environment,
    )
    srdf = parse_srdf(expansion.urdf, request.label)
    srdf.discovered = request.discovered
    outputs: dict[str, str] = {}
    text = json.dumps(srdf.to_dict(), indent=1, sort_keys=True) + "\n"
    write_output(Path(request.output), text.encode(), outputs)
    return {"outputs": outputs, "discovered": [f for f in expansion.files if f != str(source)]}
