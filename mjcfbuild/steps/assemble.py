"""Step ``assemble``: the robot model from the plan, mesh products and decompositions."""

from __future__ import annotations

import json
import os
from pathlib import Path

from mjcfbuild.check.loading import COPIES_KEY, SOURCES_KEY, copy_entries, source_entries
from mjcfbuild.collision.policy import CollisionChoice
from mjcfbuild.compose.attach import AttachedPart
from mjcfbuild.errors import CheckError
from mjcfbuild.failpoints import failpoint
from mjcfbuild.fsutil import md5_file, remove_stale_temp_files
from mjcfbuild.inputs.combine import combine
from mjcfbuild.inputs.model import Inputs, inputs_from_dict
from mjcfbuild.manifest.models import MujocoInputs
from mjcfbuild.manifest.mujoco_inputs import native_inputs
from mjcfbuild.manifest.simulation import ActuatorSettings
from mjcfbuild.meshes.product import read_product
from mjcfbuild.mjcf.assemble import Assembly, AssemblyOptions, assemble
from mjcfbuild.mjcf.bodies import floating_base
from mjcfbuild.mjcf.inertia import InertiaPolicy
from mjcfbuild.mjcf.prepared import Decomposition
from mjcfbuild.mjstopped import SimulationStopped, simulating
from mjcfbuild.ownership import refuse_foreign
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import AssemblePayload
from mjcfbuild.steps.plan_record import read_plan
from mjcfbuild.urdf.model import Robot


def run(payload: dict) -> dict:
    """Assemble the model, publish its assets, then write the model file and the report."""
    request = AssemblePayload.from_dict(payload)
    plan = read_plan(Path(request.plan))
    robot = plan.robot_model()
    products = {
        mesh_id: read_product(Path(summary)) for mesh_id, summary in request.products.items()
    }
    product_dirs = {mesh_id: Path(folder) for mesh_id, folder in request.product_dirs.items()}
    choices = [CollisionChoice.from_dict(choice) for choice in request.choices]
    decompositions = []
    for entry in request.decompositions:
        summary = json.loads(Path(entry.summary).read_text())
        decompositions.append(
            Decomposition(
                entry.mesh_id,
                entry.params,
                Path(entry.folder),
                summary["parts"],
                summary["files"],
            )
        )
    inputs, input_warnings = _inputs(request)
    control = plan.control()
    matrix = _read(request.self_collision)
    srdf = _read(request.srdf)
    home_state, home_from = _srdf_home(srdf, robot, request)
    options = AssemblyOptions(
        inputs=inputs,
        control=control,
        gazebo=plan.gazebo(),
        actuators=ActuatorSettings(**request.actuators),
        motors=request.motors,
        home=request.home,
        home_state=home_state,
        home_from=home_from,
        excludes=[tuple(pair) for pair in (matrix or {}).get("excludes", [])],
        manifest_label=request.manifest_label,
        forcerange_at=request.forcerange_at,
        fuse_static=request.fuse_static,
        free_joint=request.free_joint,
        floating=floating_base(robot, request.free_joint),
        link_sites=request.link_sites,
        max_hull_vertices=request.max_hull_vertices,
        inertia=InertiaPolicy(**request.inertia),
        header=request.header,
        choices=choices,
        decompositions=decompositions,
        parts=[AttachedPart.from_dict(entry.to_dict()) for entry in request.mjcf_parts],
    )
    try:
        with simulating("the build's trials of the model"):  # a trial names itself
            assembly = assemble(robot, products, product_dirs, options)
    except SimulationStopped as stop:
        raise CheckError(stop.line, file=request.manifest_label) from None
    assembly.warnings += _placement_warnings(assembly, request.floor)
    drawn = any(link.visuals for link in robot.links)
    shapeless = drawn and not any(link.collisions for link in robot.links)
    if shapeless and not choices and not options.floating:
        # A floating robot's stand says it has nothing to stand on; a fixed one said nothing.
        assembly.warnings.append(
            "the model has no collision geometry (the URDF has no <collision>, and no "
            "collision rule makes any): nothing of it touches the floor, an object or itself; "
            "set collision.default: visual in robot.yaml to collide with its visual shapes"
        )

    # A model the build may not write (edited by hand) stops the step before any asset
    # changes: the hand-tuned model must not be left pointing at new geometry.
    refuse_foreign(Path(request.output), assembly.xml)
    outputs: dict[str, str] = {}
    assets_dir = Path(request.assets_dir)
    report_path = Path(request.report)
    previous = _previous_assets(report_path)
    assets_dir.mkdir(parents=True, exist_ok=True)
    remove_stale_temp_files(assets_dir)
    for name, source in sorted(assembly.assets.items()):
        write_output(assets_dir / name, Path(source).read_bytes(), outputs)
    for name, digest in sorted(previous.items()):
        if name in assembly.assets or name != Path(name).name or name.startswith("."):
            continue  # still used, or not a file of assets/
        stale = assets_dir / name
        if digest is not None and stale.is_file() and _differs(stale, digest):
            # Edited since the build wrote it: the user's now, and no build would write it back
            assembly.warnings.append(
                f"assets/{name}: edited since mjcfbuild wrote it, and the model no longer uses "
                "it; kept (remove it if it is to go)"
            )
            continue
        stale.unlink(missing_ok=True)
    if not any(assets_dir.iterdir()):
        os.rmdir(assets_dir)
    report = {
        "assets": sorted(assembly.assets),
        "asset_md5": {name: outputs[str(assets_dir / name)] for name in sorted(assembly.assets)},
        # Lets the check and previews read the products MuJoCo has cached (check.loading).
        SOURCES_KEY: source_entries(assembly.assets, report_path.parent),
        COPIES_KEY: copy_entries(assembly.reads, report_path.parent),
        "repairs": [repair.__dict__ for repair in assembly.repairs],
        "warnings": assembly.warnings,
        "bodies": assembly.bodies,
        "geoms": assembly.geoms,
        "readiness": assembly.readiness.to_dict() if assembly.readiness else None,
        "self_collision": matrix,
    }
    if assembly.geometry_masses:  # robot.yaml's inertia.missing: geometry
        report["geometry_masses"] = [record.to_dict() for record in assembly.geometry_masses]
    write_output(
        report_path, (json.dumps(report, indent=1, sort_keys=True) + "\n").encode(), outputs
    )
    lowest = assembly.readiness.lowest_point if assembly.readiness else None
    floor = {"lowest_point": lowest}
    write_output(
        Path(request.floor_record), (json.dumps(floor, sort_keys=True) + "\n").encode(), outputs
    )
    failpoint("assemble")
    # The model is written last. If the build stops before this, the step has not succeeded
    # and the next build does it again, so an old model never passes for a current one.
    write_output(Path(request.output), assembly.xml, outputs)
    return {
        "outputs": outputs,
        "warnings": input_warnings
        + assembly.warnings
        + [repair.describe() for repair in assembly.repairs],
    }


def _inputs(request: AssemblePayload) -> tuple[Inputs, list[str]]:
    """The MuJoCo inputs of the URDF, the inputs file and robot.yaml, combined."""
    sources = [inputs_from_dict(request.inputs["urdf"])]
    if request.inputs["file"]:
        sources.append(inputs_from_dict(request.inputs["file"]))
    native = MujocoInputs.model_validate(request.inputs["native"])
    sources.append(native_inputs(native, request.manifest_label))
    return combine(sources)


def _placement_warnings(assembly: Assembly, floor: float | str) -> list[str]:
    """A fixed-base robot reaching below the scene's floor at home, and how to fix it."""
    lowest = assembly.readiness.lowest_point if assembly.readiness else None
    if lowest is None or floor == "auto" or lowest["height"] >= float(floor) - 1e-3:
        return []
    # A model with nothing to collide is placed by what is drawn (control.apply).
    drawn = " (its visual geometry: nothing of the model collides)" if lowest.get("visual") else ""
    return [
        f"at home, body '{lowest['body']}' reaches {float(floor) - lowest['height']:.3g} m below "
        f"the scene's floor{drawn}; set placement: {{floor: auto}} to put the floor under the "
        "robot, or options.free_joint: true for a robot that stands on its own"
    ]


def _read(path: str | None) -> dict | None:
    return json.loads(Path(path).read_text()) if path else None


def _differs(path: Path, digest: str) -> bool:
    """Whether ``path`` no longer holds the bytes of MD5 ``digest`` (one that cannot be read
    counts as unedited, as engine.written.edited takes it)."""
    try:
        return md5_file(path) != digest
    except OSError:
        return False


def _previous_assets(report_path: Path) -> dict[str, str | None]:
    """The assets the last assembly published, each with the MD5 of what it wrote (None where
    its report does not say)."""
    try:
        report = json.loads(report_path.read_text())
        digests = report.get("asset_md5") or {}
        return {name: digests.get(name) for name in report["assets"]}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return {}


def _srdf_home(
    srdf: dict | None, robot: Robot, request: AssemblePayload
) -> tuple[dict[str, float] | None, str | None]:
    """The SRDF pose that is home (the group_state robot.yaml names, else a floating robot's
    standing pose; see selfcollision.discover) and where it comes from, for the report."""
    if not srdf:
        return None, None
    from mjcfbuild.selfcollision.srdf import Srdf, home_state

    parsed = Srdf.from_dict(srdf)
    joints = {joint.name for joint in robot.joints}
    floating = floating_base(robot, request.free_joint)
    name, state = home_state(parsed, joints, request.srdf_home or "home", floating)
    if name is None:
        return None, None
    found = ", found beside the description" if parsed.discovered else ""
    return state, f"group_state '{name}' of {parsed.label}{found}"
