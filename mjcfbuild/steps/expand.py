"""Step ``expand``: the declared source as URDF text, and the files it was made from."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.failpoints import failpoint
from mjcfbuild.sources.expand import XacroWarning, expand_source
from mjcfbuild.sources.origins import origins_json
from mjcfbuild.steps.depfile import Depfile
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import ExpandPayload


def run(payload: dict) -> dict:
    """Expand (xacro) or read (URDF, description) the source into its ``output``."""
    request = ExpandPayload.from_dict(payload)
    source = Path(request.source)
    expansion = expand_source(
        source,
        request.kind == "xacro",
        request.args,
        request.packages,
        request.environment,
        request.args_key or None,
        request.written,
    )
    outputs: dict[str, str] = {}
    failpoint("expand")  # in the build process for a URDF: the tests interrupt the build here
    write_output(Path(request.output), expansion.urdf, outputs)
    write_output(Path(request.origins), origins_json(expansion.origins), outputs)
    depfile = Path(request.depfile)
    Depfile(expansion.files, expansion.missing, expansion.environment, expansion.globs).write(
        depfile
    )
    return {
        "outputs": outputs,
        "discovered": [f for f in expansion.files if f != str(source)],
        "warnings": [
            *(_said(warning, request.base_dir) for warning in expansion.warnings),
            *_ignored_args(expansion.ignored_args, request.empty_args),
        ],
    }


def _said(warning: XacroWarning, base_dir: str) -> str:
    """One of xacro's warnings as a build warning: at its file (relative to robot.yaml's
    folder, as the report names files) and line, marked as xacro's."""
    file = Path(warning.file)
    if base_dir and file.is_relative_to(base_dir):
        file = file.relative_to(base_dir)
    where = f"{file}:{warning.line}" if warning.line else str(file)
    inside = f" (in macro '{warning.macro}')" if warning.macro else ""
    return f"{where}: xacro warns{inside}: {warning.message}"


def _ignored_args(defaults: dict[str, str], where: dict[str, str]) -> list[str]:
    """A warning for each argument given an empty value that xacro ignored for a default that
    is not empty (``defaults``), at its place in robot.yaml (``where``)."""
    return [
        f"{where.get(name, name)}: the empty value is ignored, as the xacro command ignores "
        f"'{name}:='; the default '{default}' applies (give a value, or leave the argument out)"
        for name, default in sorted(defaults.items())
    ]
