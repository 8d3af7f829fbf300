"""Step ``check``: prove the built model against its URDF (see mjcfbuild.check)."""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.check.contacts import part_bodies
from mjcfbuild.check.loading import asset_sources, compile_model
from mjcfbuild.check.model_check import CheckOptions, CheckReport, check_model
from mjcfbuild.errors import CheckError
from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import CheckPayload, MjcfPartFiles
from mjcfbuild.steps.plan_record import read_plan
from mjcfbuild.urdf.transforms import vec3


def run(payload: dict) -> dict:
    """Check the model; write the results (also when a check fails, for the report)."""
    request = CheckPayload.from_dict(payload)
    report = check_built(request)
    outputs: dict[str, str] = {}
    write_results(report, Path(request.output), outputs)
    if report.failures:
        more = len(report.failures) - 1
        source = read_plan(Path(request.plan)).robot_model().source
        file, line, text = _located(report.failures[0], source, request.model_label)
        raise CheckError(
            f"check: {text}",
            file=file,
            line=line,
            hint=f"{more} more failure{'s' if more > 1 else ''} in the report" if more else None,
        )
    return {"outputs": outputs, "warnings": check_warnings(report)}


def check_built(request: CheckPayload) -> CheckReport:
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
    report = check_model(
        robot,
        Path(request.model),
        Path(request.scene),
        repaired,
        CheckOptions(**request.options),
        readiness=assembly.get("readiness") or {},
        reference=_read_reference(Path(request.reference)),
        sources=sources,
        part_bodies=part_bodies(request.mjcf_parts),
    )
    if request.mjcf_parts and report.results.get("loads"):
        _check_parts(report, Path(request.model), request.mjcf_parts, request.options, sources)
    add_runtime_check(report, Path(request.model), plan.control(), sources)
    gazebo = plan.gazebo()
    if gazebo:
        # What each Gazebo sensor became, and what of it MuJoCo does not model (noise, rates).
        report.results["gazebo_sensors"] = [
            {
                "name": sensor.name,
                "type": sensor.type,
                "reference": sensor.reference,
                "modelled": sensor.kind is not None,
                "not_modelled": sensor.not_modelled,
            }
            for sensor in gazebo
        ]
    return report


def write_results(report: CheckReport, path: Path, outputs: dict[str, str]) -> None:
    """check.json: whether it passes, the failures and every result."""
    data = {"passes": report.passes, "failures": report.failures, **report.results}
    write_output(path, (json.dumps(data, indent=1, sort_keys=True) + "\n").encode(), outputs)


def check_warnings(report: CheckReport) -> list[str]:
    """What the check found worth a warning that is not a failure."""
    plausibility = report.results.get("plausibility") or {}
    return (
        _standing_notes(report.results)
        + plausibility.get("warnings", [])
        + (report.results.get("mujoco_ros2_control") or {}).get("warnings", [])
    )


def add_runtime_check(
    report: CheckReport, model_path: Path, control: Ros2Control, sources: dict[str, Path]
) -> None:
    """The mujoco_ros2_control section, where the description has a <ros2_control> block."""
    if not report.results.get("loads") or not (control.joints or control.sensors):
        return
    from mjcfbuild.check.runtime import check_runtime

    results, failures, warnings = check_runtime(compile_model(model_path, sources), control)
    report.results["mujoco_ros2_control"] = {**results, "warnings": warnings}
    report.failures += failures


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
    report: CheckReport,
    model_path: Path,
    parts: list[MjcfPartFiles],
    options: dict,
    sources: dict[str, Path],
) -> None:
    """Compare every MJCF part with the part compiled alone; add results and failures."""
    from mjcfbuild.check.parts import PartReference, check_part

    model = compile_model(model_path, sources)
    tolerance = max(options["position_tolerance"], options["rotation_tolerance"])
    results = {}
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
        results[entry.prefix] = result.to_dict()
        where = f"MJCF part {entry.prefix} ({entry.label})"
        if result.missing:
            report.failures.append(f"{where}: {', '.join(result.missing)} not in the model")
        report.failures += [f"{where}: {problem}" for problem in result.problems]
        if result.max_position_error > options["position_tolerance"] or (
            result.max_rotation_error > options["rotation_tolerance"]
        ):
            report.failures.append(
                f"{where}: body '{result.worst_body}' is {result.max_position_error:.3g} m and "
                f"{result.max_rotation_error:.3g} rad from where the part alone puts it"
            )
    report.results["parts"] = results


def _standing_notes(results: dict) -> list[str]:
    """A warning when a floating robot cannot stand without a controller (the stand test
    fails the check of one that could but does not)."""
    why = results.get("needs_controller")
    if not why:
        return []
    if (results.get("stand") or {}).get("fell_without_controller"):
        return [f"the robot cannot stand without a controller: {why}"]
    return [
        f"the robot cannot stand without a controller: {why}; the stand test was not run, "
        "and the model holds its joints, not its balance"
    ]
