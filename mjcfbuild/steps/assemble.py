"""Step ``assemble``: the robot model from the plan and the mesh products, and its assets."""

from __future__ import annotations

import json
import os
from pathlib import Path

from mjcfbuild.fsutil import remove_stale_temp_files
from mjcfbuild.mjcf.assemble import AssemblyOptions, assemble
from mjcfbuild.mjcf.inertia import InertiaPolicy
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.urdf.model import robot_from_dict


def run(payload: dict) -> dict:
    """Assemble the model, publish its assets, then write the model file and the report."""
    plan = json.loads(Path(payload["plan"]).read_text())
    robot = robot_from_dict(plan["robot"])
    products = {
        mesh_id: json.loads(Path(summary).read_text())
        for mesh_id, summary in payload["products"].items()
    }
    product_dirs = {mesh_id: Path(folder) for mesh_id, folder in payload["product_dirs"].items()}
    options = AssemblyOptions(
        fuse_static=payload["fuse_static"],
        free_joint=payload["free_joint"],
        link_sites=payload["link_sites"],
        inertia=InertiaPolicy(**payload["inertia"]),
        header=payload["header"],
    )
    assembly = assemble(robot, products, product_dirs, options)

    outputs: dict[str, str] = {}
    assets_dir = Path(payload["assets_dir"])
    report_path = Path(payload["report"])
    previous = _previous_assets(report_path)
    assets_dir.mkdir(parents=True, exist_ok=True)
    remove_stale_temp_files(assets_dir)
    for name, source in sorted(assembly.assets.items()):
        write_output(assets_dir / name, Path(source).read_bytes(), outputs)
    for name in previous - set(assembly.assets):
        (assets_dir / name).unlink(missing_ok=True)
    if not any(assets_dir.iterdir()):
        os.rmdir(assets_dir)
    report = {
        "assets": sorted(assembly.assets),
        "repairs": [repair.__dict__ for repair in assembly.repairs],
        "warnings": assembly.warnings,
        "bodies": assembly.bodies,
        "geoms": assembly.geoms,
    }
    write_output(
        report_path, (json.dumps(report, indent=1, sort_keys=True) + "\n").encode(), outputs
    )
    # The model goes last: while it is older than its assets, the next build redoes this step.
    write_output(Path(payload["output"]), assembly.xml, outputs)
    return {
        "outputs": outputs,
        "warnings": assembly.warnings + [repair.describe() for repair in assembly.repairs],
    }


def _previous_assets(report_path: Path) -> set[str]:
    try:
        return set(json.loads(report_path.read_text())["assets"])
    except (OSError, ValueError, KeyError):
        return set()
