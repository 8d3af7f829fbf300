"""The build report as a page people read (``report/report.md``), from ``report.json``'s data.

What the check found comes first, then actuators, home and self-collision, mesh statistics,
the products. :mod:`mjcfbuild.engine.report` gathers the data. Every name and message goes
through :mod:`mjcfbuild.markup`: a link named like a picture or a table stays text.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from mjcfbuild.check.findings import BodyFinding
from mjcfbuild.check.results import CheckResults, GazeboSensor, Runtime
from mjcfbuild.check.tuning_table import tuning_lines
from mjcfbuild.markup import markdown_block, markdown_code, markdown_target
from mjcfbuild.markup import markdown_text as md


def markdown(report: dict, place: Callable[[str], str] = str) -> str:
    """The human report; ``place`` names a ``file:line`` of an expanded URDF where its
    element was written, as the warnings (placed by the build) do."""
    lines = [f"# {md(report['robot'])}: build report", ""]
    lines.append(
        f"Model {markdown_code(report['model'])} ({report.get('bodies') or '?'} bodies, "
        f"{report.get('geoms') or '?'} geoms, {len(report['assets'])} asset files), "
        f"scene {markdown_code(report['scene'])}."
    )
    lines.append("")
    checked = report.get("check")
    results = CheckResults.from_dict(checked) if checked else None
    lines += _checks(results, report.get("warnings") or [], report.get("check_not_run"))
    lines += _control(report.get("readiness") or {})
    lines += tuning_lines(report.get("tuning") or {})  # issue 33
    lines += _self_collision(report.get("self_collision"))
    lines += _plausibility(report, results, place)
    lines += _training(report.get("training"))
    if report["repairs"]:
        lines += [
            "## Inertia repairs",
            "",
            "| body | problem | before | after |",
            "|---|---|---|---|",
        ]
        lines += [
            f"| {md(r['body'])} | {md(r['problem'])} | {md(r['before'])} | {md(r['after'])} |"
            for r in report["repairs"]
        ]
        lines.append("")
    lines += _geometry_masses(report.get("geometry_masses") or [])
    if report["warnings"]:
        lines += ["## Warnings", ""] + [f"- {md(w)}" for w in report["warnings"]] + [""]
    meshes = (results.meshes if results else None) or []
    if meshes:
        lines += [
            "## Meshes",
            "",
            "| body | visual vertices | visual faces | collision vertices | collision faces "
            "| convex parts |",
            "|---|---:|---:|---:|---:|---:|",
        ]
        lines += [
            f"| {md(m.body)} | {m.visual_vertices} | {m.visual_faces} | "
            f"{m.collision_vertices} | {m.collision_faces} | {m.convex_parts} |"
            for m in meshes
        ]
        lines.append("")
    lines += _decomposition_lines(report.get("decompositions") or [])
    lines += _product_lines(report.get("products"))
    if report["previews"]:
        lines += ["## Previews", ""]
        lines += [
            f"![{md(Path(p).stem.replace('_', ' '))}]({markdown_target(p)})"
            for p in report["previews"]
        ]
        lines.append("")
    return "\n".join(lines)


def _decomposition_lines(rows: list[dict]) -> list[str]:
    """The decompositions table; concavities in CoACD's units (see collision/concavity.py)."""
    if not rows:
        return []
    lines = [
        "## Convex decompositions",
        "",
        "Concavity: how far the hull, or the union of the parts, stands off the mesh, relative "
        "to half the mesh's largest extent (the units of CoACD's threshold).",
        "",
        "| mesh | how | parts | hull concavity | concavity |",
        "|---|---|---:|---:|---:|",
    ]
    lines += [
        f"| {md(r['name'])} | {'hull kept' if r['method'] == 'hull' else 'CoACD'} "
        f"| {r['parts']} | {_number(r['hull_concavity'])} | {_number(r['concavity'])} |"
        for r in rows
    ]
    return [*lines, ""]


def _product_lines(products: dict | None) -> list[str]:
    """How many mesh products and decompositions the model is made of. Where each came from
    and how long it took changes from run to run: build-stats.json has it, not the report."""
    if not products or not (products.get("meshes") or products.get("decompositions")):
        return []
    return [
        "## Products (meshes, decompositions)",
        "",
        f"{_count(products['meshes'], 'mesh file')} converted, "
        f"{_count(products['decompositions'], 'collision mesh', 'collision meshes')} "
        "decomposed. Where each came from (computed here, on a cluster, or from a cache) and "
        "the time each task took: `.mjcfbuild/build-stats.json` in the output folder, which "
        "changes from build to build and is not for version control.",
        "",
    ]


def verdict(results: CheckResults, warnings: list[str]) -> str:
    """The report's one-line result: "all checks pass" only when nothing failed, the robot
    needs nothing the checks assumed it has, and the build warned of nothing; otherwise what
    comes first."""
    if not results.passes:
        failures = results.failures
        first = f": {md(failures[0])}" if failures else ""
        more = f" (and {len(failures) - 1} more, below)" if len(failures) > 1 else ""
        return f"**checks failed**{first}{more}"
    caveats = results.caveats(md)
    if caveats:
        return f"checks pass, but {'; '.join(caveats)}"
    if warnings:
        count = f"{len(warnings)} warning{'s' if len(warnings) > 1 else ''}"
        return f"checks pass with {count} (see Warnings): {md(warnings[0])}"
    return "all checks pass"


def _checks(
    results: CheckResults | None, warnings: list[str], not_run: str | None = None
) -> list[str]:
    if results is None:
        why = (
            f"Not run on this model: it was built with {not_run}; `mjcfbuild check` checks it."
            if not_run
            else "Not run (check.enabled is false, or the build stopped before)."
        )
        return ["## Checks", "", why, ""]
    lines = ["## Checks", "", f"Result: {verdict(results, warnings)}.", ""]
    for failure in results.failures:
        lines.append(f"- {md(failure)}")
    if results.failures:
        lines.append("")
    lines += ["| check | result |", "|---|---|"]
    lines += results.table_rows()
    lines.append("")
    contacts = results.resting_contacts
    if contacts and contacts.pairs:
        lines += ["### Robot bodies touching at home", ""]
        lines += [
            f"- {md(p.body1)} and {md(p.body2)} ({md(p.pose)} pose, {p.depth:.3g} m deep)"
            for p in contacts.pairs
        ]
        lines += ["", "To let them be, add to the raw inputs:", ""]
        lines += [*markdown_block(contacts.exclude, "xml"), ""]
    return lines + _runtime(results.mujoco_ros2_control) + _gazebo(results.gazebo_sensors)


def _motor(actuator: dict) -> str:
    """The motor behind an actuator (issue 33), if a rule named one."""
    from mjcfbuild.control.motors import URDF_LIMITS

    motor = actuator.get("motor")
    if not motor:
        return ""
    if motor["motor"] == URDF_LIMITS:
        return ", URDF speed line"
    return f", motor {md(motor['motor'])}"


def _replaced(actuator: dict) -> str:
    """The placeholder effort an actuator's force range replaced, if any."""
    effort = actuator.get("placeholder_effort")
    return f" (URDF effort {effort:g}, a placeholder)" if effort else ""


def _geometry_masses(records: list[dict]) -> list[str]:
    """The links given the mass of their geometry (robot.yaml's inertia.missing: geometry)."""
    if not records:
        return []
    lines = [
        "## Masses from geometry",
        "",
        f"{len(records)} link{'s' if len(records) > 1 else ''} without a mass in the URDF "
        f"(no <inertial>, or mass 0) weighed as MuJoCo weighs geometry, at "
        f"{records[0]['density']:g} kg/m^3 (robot.yaml's inertia.missing: geometry): the "
        "model has these masses, the URDF does not.",
        "",
        "| link | from its | mass (kg) | centre of mass (link frame, m) |",
        "|---|---|---:|---|",
    ]
    for record in records:
        com = ", ".join(f"{v:.4g}" for v in record["com"])
        lines.append(
            f"| {md(record['link'])} | {record['geometry']} geometry | {record['mass']:.6g} "
            f"| ({com}) |"
        )
    return [*lines, ""]


def _control(readiness: dict) -> list[str]:
    """The actuators (with where each came from), the home pose and the floating base."""
    if not readiness:
        return []
    lines = ["## Actuators", ""]
    if readiness.get("actuators"):
        lines += ["| actuator | joint | type | from | kp | kv | ctrlrange | forcerange |"]
        lines += ["|---|---|---|---|---:|---:|---|---|"]
        for a in readiness["actuators"]:
            lines.append(
                f"| {md(a['name'])} | {md(a['joint'])} | {md(a['type'])} | {md(a['source'])}"
                f"{_motor(a)}"
                f"{', weight-bearing' if a.get('weight_bearing') else ''}"
                f"{_armature(a)} | "
                f"{_number(a.get('kp'))} | {_number(a.get('kv'))} | {_range(a.get('ctrlrange'))} "
                f"| {_range(a.get('forcerange'))}{_replaced(a)} |"
            )
    else:
        lines.append("None.")
    if readiness.get("passive"):
        passive = ", ".join(md(joint) for joint in readiness["passive"])
        lines += ["", f"Passive joints (actuator type none): {passive}"]
    lines += ["", "## Home pose", ""]
    if readiness.get("home"):
        lines += ["| joint | position | from |", "|---|---:|---|"]
        lines += [
            f"| {md(h['joint'])} | {h['value']:.6g} | {md(h['source'])} |"
            for h in readiness["home"]
        ]
    if readiness.get("home_from"):
        what = "computed" if readiness["home_from"].startswith("crouch") else "srdf"
        lines += ["", f"The `{what}` values are the {md(readiness['home_from'])}."]
    if readiness.get("base_height") is not None:
        lines += [
            "",
            f"The floating base was raised {readiness['base_height']:.4g} m to stand on the floor.",
        ]
    stance = readiness.get("stance")
    if stance:
        if stance.get("can_stand"):
            lines += [
                "",
                f"At home it stands on {', '.join(md(foot) for foot in stance['feet'])}: they span "
                f"{stance['area'] * 1e4:.0f} cm2, its centre of mass "
                f"{stance['com_margin'] * 1000:.0f} mm inside their edge. Weight-bearing "
                "servos are stiffened to hold it (docs/simulation.md).",
            ]
        else:
            lines += ["", f"It cannot stand on its own: {md(stance['why_not'])}."]
    lines.append("")
    return lines


def _training(training: dict | None) -> list[str]:
    """The training variant: its collision shapes, contacts, notes and Warp figures."""
    if not training:
        return []
    kinds: dict[str, int] = {}
    for shapes in training.get("geoms", {}).values():
        for kind in shapes:
            kinds[kind] = kinds.get(kind, 0) + 1
    shapes = ", ".join(f"{count} {md(kind)}" for kind, count in sorted(kinds.items()))
    floor = ", ".join(md(body) for body in training.get("floor", [])) or "none"
    lines = [
        "## Training variant",
        "",
        f"{markdown_code(training['file'])}: collision shapes {shapes or 'none'}; "
        f"floor contacts: {floor}; "
        f"{len(training.get('pairs', []))} self-collision body pairs.",
        "",
    ]
    solver = training.get("solver")
    if solver:
        lines += [
            f"Solver for a {solver['device'].upper()}: {solver['solver']}, "
            f"{_count(solver['iterations'], 'iteration')}, "
            f"{_count(solver['ls_iterations'], 'line-search iteration')} "
            "(`output.training.device`, docs/simulation.md).",
            "",
        ]
    lines += [f"- {md(note)}" for note in training.get("notes", [])]
    warp = training.get("warp")
    if warp:
        full, variant = warp["full"], warp["variant"]
        lines += [
            "",
            f"In MuJoCo Warp ({variant['worlds']} worlds, {variant['steps']} steps with noise "
            f"on ctrl, `check --warp`): {md(warp['behaviour'])}.",
            "",
            "| model | collision geoms | contact pairs | steps/s |",
            "|---|---:|---:|---:|",
        ]
        for name, row in (("full", full), ("variant", variant)):
            lines.append(
                f"| {name} | {row['collision_geoms']} | {row['contact_pairs']} "
                f"| {row['steps_per_second']:.0f} |"
            )
        lines += [f"- check failed: {md(failure)}" for failure in warp.get("failures", [])]
        gpu = warp.get("gpu")
        if gpu and "error" in gpu:
            lines += ["", f"- check failed on the GPU: {md(gpu['error'])}"]
        elif gpu:
            rows = (("full", gpu["full"]), ("variant", gpu["variant"]))
            lines += [
                "",
                f"On {md(gpu['device'])} ({gpu['variant']['worlds']} worlds): "
                f"{md(gpu['behaviour'])}; "
                + ", ".join(f"{n} {r['steps_per_second']:.0f} steps/s" for n, r in rows)
                + ".",
            ]
            lines += [f"- check failed on the GPU: {md(f)}" for f in gpu["failures"]]
    else:
        lines += ["", "Not yet measured in MuJoCo Warp: run `mjcfbuild check --warp`."]
    lines.append("")
    return lines


def _count(number: int, noun: str, plural: str = "") -> str:
    """``1 iteration``, ``5 iterations``."""
    return f"{number} {noun if number == 1 else plural or noun + 's'}"


def _self_collision(matrix: dict | None) -> list[str]:
    """The collision matrix: every body pair that is excluded, with its reason."""
    if not matrix:
        return []
    pairs = matrix.get("pairs", [])
    excluded = [p for p in pairs if p["exclude"]]
    counts: dict[str, int] = {}
    for pair in pairs:
        counts[pair["reason"]] = counts.get(pair["reason"], 0) + 1
    summary = ", ".join(f"{count} {md(reason)}" for reason, count in sorted(counts.items()))
    lines = [
        "## Self-collision",
        "",
        f"{len(pairs)} body pairs ({summary}) over {matrix.get('samples')} sampled "
        f"configurations; {len(excluded)} excluded, {len(matrix.get('excludes', []))} of them "
        "by a contact exclude (MuJoCo already skips parent and child).",
        "",
    ]
    if excluded:
        lines += ["| body 1 | body 2 | reason | in collision |", "|---|---|---|---:|"]
        # MuJoCo never reports parent-child contacts, so adjacent pairs have no fraction.
        lines += [
            f"| {md(p['body1'])} | {md(p['body2'])} | {md(p['reason'])} | "
            f"{'-' if p['reason'] == 'adjacent' else format(p['fraction'], '.0%')} |"
            for p in excluded
        ]
        lines.append("")
    return lines


def _number(value) -> str:
    return f"{value:.4g}" if value is not None else ""


def _range(values) -> str:
    return f"[{values[0]:.4g}, {values[1]:.4g}]" if values else ""


def _plausibility(
    report: dict, results: CheckResults | None, place: Callable[[str], str] = str
) -> list[str]:
    """Where the meshes are: the plausibility test, COLLADA up axes, MJCF parts' own contacts."""
    found = results.plausibility if results else None
    decisions = report.get("up_axis") or []
    contacts = results.resting_contacts if results else None
    inside = contacts.inside_parts if contacts else []
    if found is None and not decisions and not inside:
        return []
    lines = ["## Mesh plausibility", ""]
    if found is not None:
        findings = found.findings
        lines.append(
            f"{found.bodies} bodies tested (centre of mass inside its own geometry, "
            "visual and collision geometry overlapping, a mass its geometry can hold): "
            f"{len(findings) or 'none'} named."
        )
        lines.append("")
        if findings:
            lines += ["| body | result | problems | likely cause |", "|---|---|---|---|"]
            lines += [
                f"| {_named(f, place)} | {'fails' if f.fails else 'warning'} | "
                f"{md('; '.join(f.problems))} | {md(f.detail)} |"
                for f in findings
            ]
            lines.append("")
    if decisions:
        turned = [d for d in decisions if d.get("turned")]
        lines += [
            f"COLLADA up axis: {len(turned)} of {len(decisions)} DAE files tagged other than "
            "Z-up were turned.",
            "",
            "| mesh | tag | turned | why |",
            "|---|---|---|---|",
        ]
        lines += [
            f"| {md(d['mesh'])} | {md(d.get('tag'))} | {'yes' if d.get('turned') else 'no'} | "
            f"{md(d.get('reason'))} |"
            for d in decisions
        ]
        lines.append("")
    if inside:
        lines += [
            "Bodies of one MJCF part touching at home (the part's own contact behaviour; "
            "not a failure):",
            "",
        ]
        lines += [
            f"- {md(p.body1)} and {md(p.body2)} in {md(p.part)} ({md(p.pose)} pose, "
            f"{p.depth:.3g} m deep)"
            for p in inside
        ]
        lines.append("")
    return lines


def _named(finding: BodyFinding, place: Callable[[str], str] = str) -> str:
    """A plausibility finding's body, or what else it names (a link, the robot), with the
    URDF line to fix where there is one (as ``place`` names it)."""
    subject = finding.subject
    name = finding.body if subject == "body" else f"{subject} {finding.body}"
    return md(f"{name} ({place(finding.where)})" if finding.where else name)


def _armature(actuator: dict) -> str:
    """The armature the build gave a weight-bearing joint, if it did."""
    armature = actuator.get("armature")
    return f" (armature {armature:.3g} added)" if armature else ""


def _gazebo(sensors: list[GazeboSensor] | None) -> list[str]:
    """The URDF's Gazebo sensors: which have an MJCF counterpart, and what it does not model."""
    if not sensors:
        return []
    lines = [
        "### Gazebo sensors",
        "",
        "| sensor | type | on | not modelled |",
        "|---|---|---|---|",
    ]
    for sensor in sensors:
        missing = "the sensor" if not sensor.modelled else ", ".join(sensor.not_modelled)
        lines.append(
            f"| {md(sensor.name)} | {md(sensor.type)} | {md(sensor.reference)} | "
            f"{md(missing or '-')} |"
        )
    return [*lines, ""]


# How the runtime takes a command interface (check.runtime's record), in words.
_WAYS = {
    "direct": "direct",
    "pid": "through PID gains",
    "pid?": "through PID gains (file not read here)",
    "no pid": "NO PID GAINS (the runtime stops)",
    None: "not taken (offered, written into ctrl as is)",
}


def _runtime(runtime: Runtime | None) -> list[str]:
    """What mujoco_ros2_control finds for the <ros2_control> block (check.runtime)."""
    if not runtime:
        return []
    lines = ["### mujoco_ros2_control", ""]
    if runtime.joints:
        lines += [
            "| joint | command interfaces | actuator | kind (as the runtime classifies it) |",
            "|---|---|---|---|",
        ]
        for joint in runtime.joints:
            how = ", ".join(
                f"{name}: {_WAYS.get(way, way)}" for name, way in joint["how"].items()
            ) or ", ".join(joint["interfaces"])
            lines.append(
                f"| {md(joint['joint'])} | {md(how)} | {md(joint['actuator'] or 'none')} | "
                f"{joint['kind'] or '-'} |"
            )
        lines.append("")
    if runtime.sensors:
        lines += ["| sensor | mujoco_type | MJCF sensors (site) |", "|---|---|---|"]
        for sensor in runtime.sensors:
            found = ", ".join(
                f"{m['type']} {md(m['name'])}" + (f" ({md(m['site'])})" if m["site"] else "")
                if m["found"]
                else f"{m['type']} {md(m['name'])} MISSING"
                for m in sensor["mjcf"]
            )
            lines.append(f"| {md(sensor['sensor'])} | {md(sensor['type'])} | {found} |")
        lines.append("")
    for device in runtime.devices:
        rays = f", {device['rays']} rays" if device["kind"] == "lidar" else ""
        state = "found" if device["found"] else "MISSING"
        lines.append(f"- {device['kind']} {md(device['sensor'])}: {state}{rays}")
    if runtime.devices:
        lines.append("")
    return lines
