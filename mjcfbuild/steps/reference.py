"""Step ``reference``: what the check's independent reader (yourdfpy) reads from the URDF for
forward kinematics, kept as a record for the check (see mjcfbuild.check.reference)."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.check.reference import read_kinematics
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import ReferencePayload


def run(payload: dict) -> dict:
    """Read the URDF's kinematics and write the record (one that says why, if unreadable)."""
    request = ReferencePayload.from_dict(payload)
    record = read_kinematics(Path(request.urdf).read_bytes())
    outputs: dict[str, str] = {}
    text = json.dumps(record, indent=1, sort_keys=True) + "\n"
    write_output(Path(request.output), text.encode(), outputs)
    return {"outputs": outputs}
