"""Step ``export_urdf``: a URDF of the built model, with its mesh files."""

from __future__ import annotations

import json
import os
from pathlib import Path

from mjcfbuild.export import ExportOptions, export_urdf
from mjcfbuild.export.publish import default_asset_prefix
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import ExportUrdfPayload


def run(payload: dict) -> dict:
    """Export, write the meshes and then the URDF, and remove meshes an earlier export left."""
    request = ExportUrdfPayload.from_dict(payload)
    options = request.options
    urdf, mesh_dir = Path(request.urdf), Path(request.mesh_dir)
    prefix = options["asset_prefix"]
    if prefix is None:
        prefix = default_asset_prefix(urdf, mesh_dir)
    result = export_urdf(
        Path(request.model),
        ExportOptions(asset_prefix=prefix, sites=options["sites"], header=options["header"]),
        build_speeds(Path(request.plan), Path(request.assembly_report)),
    )
    outputs: dict[str, str] = {}
    for name, data in sorted(result.meshes.items()):
        write_output(mesh_dir / name, data, outputs)
    record = Path(request.record)
    for name in _previous_meshes(record) - set(result.meshes):
        if name == Path(name).name and not name.startswith("."):  # never outside the folder
            (mesh_dir / name).unlink(missing_ok=True)
    if mesh_dir.is_dir() and not any(mesh_dir.iterdir()):
        mesh_dir.rmdir()
    # What it wrote, by name in the output folder (the state folder's parent): what a build
    # removes once output.urdf is off or names another file (engine.outputs_off).
    out = record.parent.parent
    written = {
        "meshes": sorted(result.meshes),
        "mesh_folder": os.path.relpath(mesh_dir, out),
        "urdf": os.path.relpath(urdf, out),
    }
    write_output(record, (json.dumps(written) + "\n").encode(), {})
    write_output(urdf, result.urdf, outputs)
    return {"outputs": outputs, "warnings": [f"URDF export: {w}" for w in result.warnings]}


def build_speeds(plan: Path, assembly_report: Path) -> dict[str, float]:
    """The speed limits the build knows beyond the model (joint -> rad/s or m/s): the source
    URDF's ``<limit velocity>`` (:func:`~mjcfbuild.export.speeds.urdf_speeds`), overruled by
    the no-load speed of the drive (``motors:``) behind the joint's actuator, which is the
    model's."""
    from mjcfbuild.export.speeds import urdf_speeds
    from mjcfbuild.steps.plan_record import read_plan

    speeds = urdf_speeds(read_plan(plan).robot_model())
    try:
        assembly = json.loads(assembly_report.read_text())
    except (OSError, ValueError):
        assembly = {}
    for record in (assembly.get("readiness") or {}).get("actuators", []):
        no_load = (record.get("motor") or {}).get("no_load_speed")
        if no_load is not None and no_load > 0:
            speeds[record["joint"]] = float(no_load)
    return speeds


def _previous_meshes(record: Path) -> set[str]:
    try:
        return set(json.loads(record.read_text())["meshes"])
    except (OSError, ValueError, KeyError):
        return set()
