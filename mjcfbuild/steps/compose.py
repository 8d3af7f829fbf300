"""Step ``compose``: the expanded main source with the ``attach:`` parts joined to it."""

from __future__ import annotations

from functools import partial
from pathlib import Path

from mjcfbuild.compose.urdf import Part, compose
from mjcfbuild.sources.origins import origins_json, written_at
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.sources.uris import resolve_uri
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import ComposePayload
from mjcfbuild.urdf.transforms import vec3


def run(payload: dict) -> dict:
    """Write the composed URDF to its ``output``."""
    request = ComposePayload.from_dict(payload)
    parts = []
    for entry in request.parts:
        packages = PackageResolver(
            {name: Path(folder) for name, folder in entry.packages.items()},
            request.environment,
        )
        parts.append(
            Part(
                xml=Path(entry.urdf).read_bytes(),
                label=entry.label,
                key=entry.key,
                prefix=entry.prefix,
                to=entry.to,
                xyz=vec3(entry.xyz),
                rpy=vec3(entry.rpy),
                resolve=partial(_resolve, base_dir=Path(entry.base_dir), packages=packages),
            )
        )
    main = Path(request.main).read_bytes()
    joined: dict[int, tuple[int, int]] = {}
    text, warnings = compose(main, request.main_label, parts, Path(request.base_dir), joined)
    outputs: dict[str, str] = {}
    write_output(Path(request.output), text, outputs)
    inputs = [(request.main, request.main_label)]
    inputs += [(entry.urdf, entry.label) for entry in request.parts]
    origins = {}
    for line, (source, written) in joined.items():
        urdf, label = inputs[source]
        # Through the input's own origins (a xacro), else its line as it is shown.
        origins[line] = written_at(Path(urdf), written) or (label, written)
    write_output(Path(request.origins), origins_json(origins), outputs)
    return {"outputs": outputs, "warnings": warnings}


def _resolve(uri: str, base_dir: Path, packages: PackageResolver) -> Path:
    return resolve_uri(uri, base_dir, packages)
