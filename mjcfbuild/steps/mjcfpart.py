"""Step ``mjcfpart``: an MJCF part read and compiled alone, made ready to attach.

Writes the part normalised (see :mod:`mjcfbuild.compose.mjcf`) at full precision, a summary
of its names, joints, actuators and home for the plan stage and the assembly, content-addressed
copies of its asset files, and a depfile of every file it read (the part, its includes and its
assets), so editing any of them reruns this step and what depends on it, nothing else.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from mjcfbuild.compose.mjcf import (
    asset_files,
    content_name,
    included_files,
    load_part,
    normalise,
    summarise,
)
from mjcfbuild.errors import InputError
from mjcfbuild.mjcf.precise import precise_xml
from mjcfbuild.steps.depfile import Depfile
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import MjcfPartPayload


def run(payload: dict) -> dict:
    """Read the part at ``source``; write its normalised XML and summary."""
    request = MjcfPartPayload.from_dict(payload)
    source = Path(request.source)
    label = request.label
    spec, model = load_part(source, label)
    summary = summarise(spec, model, label)
    outputs: dict[str, str] = {}
    assets_dir = Path(request.assets_dir)
    stored: dict[str, Path] = {}
    files = [source, *included_files(source, label)]
    for _, _, path in asset_files(spec):
        if str(path) in stored:
            continue
        try:
            data = path.read_bytes()
        except OSError:
            raise InputError(
                f"the part's asset '{path.name}' cannot be read", file=label, hint=str(path)
            ) from None
        name = content_name(data, path.suffix)
        write_output(assets_dir / name, data, outputs)
        stored[str(path)] = assets_dir / name
        summary.assets[name] = str(assets_dir / name)
        files.append(path)
    summary.files = sorted({str(f) for f in files})
    normalise(spec, model, stored)
    root = precise_xml(spec)
    text = etree_text(root)
    write_output(Path(request.xml), text, outputs)
    write_output(
        Path(request.summary),
        (json.dumps(summary.to_dict(), indent=1, sort_keys=True) + "\n").encode(),
        outputs,
    )
    Depfile(summary.files, [], {}).write(Path(request.depfile))
    return {
        "outputs": outputs,
        "warnings": summary.warnings,
        "discovered": [f for f in summary.files if f != str(source)],
    }


def etree_text(root: Any) -> bytes:
    """The normalised part as bytes."""
    from lxml import etree

    return etree.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"
