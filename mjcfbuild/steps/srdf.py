"""Step ``srdf``: read the SRDF named by ``self_collision.srdf`` (expanding it if it is xacro)."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.selfcollision.srdf import parse_srdf
from mjcfbuild.sources.expand import expand_source
from mjcfbuild.steps.depfile import Depfile
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
    if request.home_state is not None and request.home_state not in srdf.states:
        _refuse_missing_state(request.home_state, list(srdf.states), request)
    outputs: dict[str, str] = {}
    text = json.dumps(srdf.to_dict(), indent=1, sort_keys=True) + "\n"
    write_output(Path(request.output), text.encode(), outputs)
    Depfile(expansion.files, expansion.missing, expansion.environment, expansion.globs).write(
        Path(request.depfile)
    )
    return {"outputs": outputs, "discovered": [f for f in expansion.files if f != str(source)]}


def _refuse_missing_state(name: str, states: list[str], request: SrdfPayload) -> None:
    """robot.yaml's home_state names a group_state the SRDF does not have: a typo, which
    would otherwise leave home at zero without a word."""
    from mjcfbuild.errors import ManifestError
    from mjcfbuild.sources.packages import did_you_mean, listing

    hint = (
        f"its group states: {listing(sorted(states))}"
        if states
        else "it has none: add a <group_state>, or remove home_state"
    )
    raise ManifestError(
        f"{request.label} has no group_state '{name}'{did_you_mean(name, states)}",
        file=f"{request.manifest_label} self_collision.home_state",
        hint=hint,
    )
