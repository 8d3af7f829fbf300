"""Step ``check``: prove the built model against its URDF (see mjcfbuild.check)."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.check.contacts import part_bodies
from mjcfbuild.check.loading import AssetSource, asset_sources, compile_model
from mjcfbuild.check.model_check import CheckOptions, check_model
from mjcfbuild.check.results import CheckResults, GazeboSensor, Runtime
from mjcfbuild.errors import CheckError
from mjcfbuild.inputs.pid_gains import PidGains
from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.mjcf.geometry_mass import GeometryMass
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import CheckPayload, MjcfPartFiles
from mjcfbuild.steps.plan_record import read_plan
from mjcfbuild.urdf.transforms import vec3


def run(payload: dict) -> dict:
    """Check the model; write the results (also when a check fails, for the report)."""
    request = CheckPayload.from_dict(payload)
    results = check_built(request)
    outputs: dict[str, str] = {}
    write_results(results, Path(request.output), outputs)
    if results.failures:
        more = len(results.failures) - 1
        source = read_plan(Path(request.plan)).robot_model().source
        file, line, text = _located(results.failures[0], source, request.model_label)
        raise CheckError(
            f"check: {text}",
            file=file,
            line=line,
            hint=f"{more} more failure{'s' if more > 1 else ''} in the report" if more else None,
        )
    return {"outputs": outputs, "warnings": results.warnings()}


def check_built(request: CheckPayload) -> CheckResults:
    """Every check of a built model: against its URDF, its MJCF parts alone and
    mujoco_ros2_control's rules. The build's check task and ``mjcfbuild check`` both run this,
    so they write the same check.json."""
    plan = read_plan(Path(request.plan))
    robot = plan.robot_model()
    try:
        assembly = json.loads(Path(request.assembly_report).read_text())
    except (OSError, ValueError):
        assembly = {}
    repaired = {repair["body"] for repair in assembly.get("repairs", [])}
    sources = asset_sources(Path(request.assembly_report))
    results = check_model(
        robot,
        Path(request.model),
        Path(request.scene),
        repaired,
        CheckOptions(**request.options),
        readiness=assembly.get("readiness") or {},
        reference=_read_reference(Path(request.reference)),
        sources=sources,
        part_bodies=part_bodies(request.mjcf_parts),
        geometry_masses=[
            GeometryMass.from_dict(record) for record in assembly.get("geometry_masses", [])
        ],
    )
    if request.mjcf_parts and results.loads:
        results = _check_parts(
            results, Path(request.model), request.mjcf_parts, request.options, sources
        )
    results = add_runtime_check(
        results,
        Path(request.model),
        plan.control(),
        _urdf_joints(plan.robot),
        sources,
        request.depfile,
        frozenset(j["name"] for j in plan.robot["joints"] if j["kind"] == "fixed"),
        _built(request),
        {name: Path(folder) for name, folder in request.packages.items()},
    )
    gazebo = plan.gazebo()
    if gazebo:
        # What each Gazebo sensor became, and what of it MuJoCo does not model (noise, rates).
        sensors = [
            GazeboSensor(
                name=sensor.name,
                type=sensor.type,
                reference=sensor.reference,
                modelled=sensor.kind is not None,
                not_modelled=sensor.not_modelled,
            )
            for sensor in gazebo
        ]
        results = results.add(gazebo_sensors=sensors)
    return results


def write_results(results: CheckResults, path: Path, outputs: dict[str, str]) -> None:
    """check.json: whether it passes, the failures and every result."""
    write_output(path, results.to_json(), outputs)


def add_runtime_check(
    results: CheckResults,
    model_path: Path,
    control: Ros2Control,
    urdf_joints: dict[str, str | None],
    sources: dict[str, AssetSource],
    depfile: str = "",
    fixed_joints: frozenset[str] = frozenset(),
    built: tuple[tuple[Path, str], ...] = (),
    packages: dict[str, Path] | None = None,
) -> CheckResults:
    """The mujoco_ros2_control section, where the description has a <ros2_control> block; the
    files it reads besides its inputs are recorded in ``depfile``. ``fixed_joints`` names the
    URDF's fixed joints (ros2_control refuses one in a block); ``built`` the model and scene
    (path and label, the scene last), which its mujoco_model param should name, and
    ``packages`` the folders its $(find pkg) stands for."""
    if depfile:
        _record_reads(control, Path(depfile))
    if not results.loads or not (
        control.joints or control.sensors or control.unknown_children or control.jointless
    ):
        return results
    from mjcfbuild.check.runtime import check_runtime
    from mjcfbuild.check.runtime_model import model_param

    model = compile_model(model_path, sources)
    gains, unloadable = _pid_gains(control)
    found, failures, warnings = check_runtime(model, control, urdf_joints, gains, fixed_joints)
    failures += unloadable
    loaded_failures, loaded_warnings = model_param(control, built, packages or {})
    failures += loaded_failures
    warnings += loaded_warnings
    runtime = Runtime(
        found["joints"], found["sensors"], found["devices"], warnings, failed=bool(failures)
    )
    return results.add(failures, mujoco_ros2_control=runtime)


def _built(request: CheckPayload) -> tuple[tuple[Path, str], ...]:
    """The model and the scene, each with the label messages give it (the scene's beside the
    model's), the scene last."""
    import os

    model, scene = Path(request.model), Path(request.scene)
    label = os.path.normpath(
        Path(request.model_label).parent / os.path.relpath(scene, model.parent)
    )
    return (model, request.model_label), (scene, label)


def _urdf_joints(robot: dict) -> dict[str, str | None]:
    """Each URDF joint of the plan's robot, with the joint it mimics (None for others)."""
    return {joint["name"]: (joint.get("mimic") or {}).get("joint") for joint in robot["joints"]}


def _record_reads(control: Ros2Control, depfile: Path) -> None:
    """The pids_config_file the section reads, in ``depfile``: a dependency where it exists,
    and where it does not, a file whose appearing reruns the check."""
    from mjcfbuild.inputs.pid_gains import pids_file
    from mjcfbuild.steps.depfile import Depfile

    path = pids_file(control.hardware)
    there = path is not None and path.exists()
    missing = path is not None and not there
    Depfile([str(path)] if there else [], [str(path)] if missing else [], {}).write(depfile)


def _pid_gains(control: Ros2Control) -> tuple[PidGains | None, list[str]]:
    """The gains of the pids_config_file the runtime's block names (None where there is none,
    or it cannot be read here), and a failure where the runtime could not load it."""
    from mjcfbuild.inputs.pid_gains import pids_file, read_pid_gains

    path = pids_file(control.hardware)
    if path is None:
        return None, []
    try:
        return read_pid_gains(path), []
    except OSError:
        return None, []
    except ValueError as exc:
        return PidGains(), [
            f"{control.at('pids_config_file')}mujoco_ros2_control: the pids_config_file {path} "
            "is no ROS parameter file "
            f"({exc}): the runtime cannot load it and stops at start-up; fix its YAML"
        ]


def _located(failure: str, source: str, model_label: str) -> tuple[str, int | None, str]:
    """(file, line, message) of a failure: one that starts ``source:line:`` (a URDF link to
    fix, which the runner then follows into a xacro file) is placed there; others are the
    model's."""
    head = f"{source}:"
    number, sep, rest = failure[len(head) :].partition(": ")
    if failure.startswith(head) and sep and number.isdigit():
        return source, int(number), rest
    return model_label, None, failure


def _read_reference(path: Path) -> dict:
    """The record of the ``reference`` task (check.reference), or one saying why there is
    none (the check then compares with mjcfbuild's own parse and says so)."""
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        return {"error": f"the reference record could not be read ({exc})"}
    return record if isinstance(record, dict) else {"error": "the reference record is not one"}


def _check_parts(
    results: CheckResults,
    model_path: Path,
    parts: list[MjcfPartFiles],
    options: dict,
    sources: dict[str, AssetSource],
) -> CheckResults:
    """Compare every MJCF part with the part compiled alone; add results and failures."""
    from mjcfbuild.check.parts import PartReference, PartResult, check_part

    model = compile_model(model_path, sources)
    tolerance = max(options["position_tolerance"], options["rotation_tolerance"])
    found: dict[str, PartResult] = {}
    failures: list[str] = []
    for entry in parts:
        reference = PartReference(
            prefix=entry.prefix,
            source=Path(entry.source),
            label=entry.label,
            to=entry.to,
            pos=vec3(entry.pos),
            quat=(entry.quat[0], entry.quat[1], entry.quat[2], entry.quat[3]),
        )
        result = check_part(model, reference, options["configurations"], options["seed"], tolerance)
        found[entry.prefix] = result
        where = f"MJCF part {entry.prefix} ({entry.label})"
        if result.missing:
            failures.append(f"{where}: {', '.join(result.missing)} not in the model")
        failures += [f"{where}: {problem}" for problem in result.problems]
        if result.max_position_error > options["position_tolerance"] or (
            result.max_rotation_error > options["rotation_tolerance"]
        ):
            failures.append(
                f"{where}: body '{result.worst_body}' is {result.max_position_error:.3g} m and "
                f"{result.max_rotation_error:.3g} rad from where the part alone puts it"
            )
    return results.add(failures, parts=found)
