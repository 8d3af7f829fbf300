"""The step of the test's own task family (test_registry.py): writes a line about the model."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import FileDependency, Output, Payload


@dataclass(frozen=True)
class ToyPayload(Payload):
    """What the toy step is given."""

    greeting: str
    model: FileDependency
    output: Output


def run(payload: dict) -> dict:
    """Write the greeting and the size of the model."""
    request = ToyPayload.from_dict(payload)
    outputs: dict[str, str] = {}
    size = Path(request.model).stat().st_size
    write_output(Path(request.output), f"{request.greeting} {size}\n".encode(), outputs)
    return {"outputs": outputs}
