"""The build report as a page people read (``report/report.md``), from ``report.json``'s data.

What the check found comes first, then actuators, home and self-collision, mesh statistics,
the product cache and the time each task took. :mod:`mjcfbuild.engine.report` gathers the data.
"""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.check.tuning_table import tuning_lines


def markdown(report: dict) -> str:
    """The human report."""
    lines = [f"# {report['robot']}: build report", ""]
    lines.append(
        f"Model `{report['model']}` ({report.get('bodies') or '?'} bodies, "
        f"{report.get('geoms') or '?'} geoms, {len(report['assets'])} asset files), "
        f"scene `{report['scene']}`."
    )
    lines.append("")
    lines += _checks(report.get("check") or {}, report.get("warnings") or [])
    lines += _control(report.get("readiness") or {})
    lines += tuning_lines(report.get("tuning") or {})  # issue 33
    lines += _self_collision(report.get("self_collision"))
    lines += _plausibility(report)
    lines += _training(report.get("training"))
    if report["repairs"]:
        lines += [
            "## Inertia repairs",
            "",
            "| body | problem | before | after |",
            "|---|---|---|---|",
        ]
        lines += [
            f"| {r['body']} | {r['problem']} | {r['before']} | {r['after']} |"
            for r in report["repairs"]
        ]
        lines.append("")
    if report["warnings"]:
        lines += ["## Warnings", ""] + [f"- {w}" for w in report["warnings"]] + [""]
    meshes = (report.get("check") or {}).get("meshes") or []
    if meshes:
        lines += [
            "## Meshes",
            "",
            "| body | visual vertices | visual faces | collision vertices | collision faces "
            "| convex parts |",
            "|---|---:|---:|---:|---:|---:|",
        ]
        lines += [
            f"| {m['body']} | {m['visual_vertices']} | {m['visual_faces']} | "
            f"{m['collision_vertices']} | {m['collision_faces']} | {m['convex_parts']} |"
            for m in meshes
        ]
        lines.append("")
    lines += _decomposition_lines(report.get("decompositions") or [])
    lines += _cache_lines(report.get("cache"))
    if report["times"]:
        lines += [
            "## Build times (when each task last ran)",
            "",
            "| task | seconds |",
            "|---|---:|",
        ]
        lines += [f"| {task} | {seconds:.2f} |" for task, seconds in report["times"].items()]
        lines.append("")
    if report["previews"]:
        lines += ["## Previews", ""]
        lines += [f"![{Path(p).stem.replace('_', ' ')}]({p})" for p in report["previews"]]
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
        "| mesh | how | parts | hull concavity | concavity | seconds |",
        "|---|---|---:|---:|---:|---:|",
    ]
    lines += [
        f"| {r['name']} | {'hull kept' if r['method'] == 'hull' else 'CoACD'} | {r['parts']} "
        f"| {_number(r['hull_concavity'])} | {_number(r['concavity'])} "
        f"| {_number(r['seconds'])} |"
        for r in rows
    ]
    return [*lines, ""]


def _cache_lines(cache: dict | None) -> list[str]:
    """Where this build's meshes and decompositions came from."""
    if not cache:
        return []
    computed = cache.get("computed", {})
    made = ", ".join(
        f"{kind} {n['here']} here, {n['on_cluster']} on the cluster" for kind, n in computed.items()
    )
    lines = [
        "## Products (meshes, decompositions)",
        "",
        f"Computed: {made or 'none'}. Local cache hits: {cache['local_hits']}.",
    ]
    if cache.get("remote"):
        lines.append(
            f"Remote cache `{cache['remote']}`: {cache['remote_hits']} hits, "
            f"{cache['remote_misses']} misses, {cache['remote_rejected']} rejected objects, "
            f"{cache['uploaded']} uploaded."
        )
    if cache.get("executor", "local") != "local":
        lines.append(f"Executor: `{cache['executor']}`.")
    return [*lines, ""]


def verdict(check: dict, warnings: list[str]) -> str:
    """The report's one-line result: "all checks pass" only when nothing failed, the robot
    needs nothing the checks assumed it has, and the build warned of nothing; otherwise what
    comes first."""
    if not check.get("passes"):
        failures = check.get("failures") or []
        first = f": {failures[0]}" if failures else ""
        more = f" (and {len(failures) - 1} more, below)" if len(failures) > 1 else ""
        return f"**checks failed**{first}{more}"
    if check.get("needs_controller"):
        ran = (check.get("stand") or {}).get("fell_without_controller")
        return (
            "checks pass, but the robot cannot stand without a controller "
            f"({check['needs_controller']})" + ("" if ran else ": the stand test was not run")
        )
    if warnings:
        count = f"{len(warnings)} warning{'s' if len(warnings) > 1 else ''}"
        return f"checks pass with {count} (see Warnings): {warnings[0]}"
    return "all checks pass"


def _checks(check: dict, warnings: list[str]) -> list[str]:
    if not check:
        return [
            "## Checks",
            "",
            "Not run (check.enabled is false, or the build stopped before).",
            "",
        ]
    lines = ["## Checks", "", f"Result: {verdict(check, warnings)}.", ""]
    for failure in check.get("failures", []):
        lines.append(f"- {failure}")
    if check.get("failures"):
        lines.append("")
    kinematics = check.get("kinematics", {})
    simulation = check.get("simulation", {})
    masses = check.get("masses", {})
    lines += ["| check | result |", "|---|---|"]
    lines.append(f"| loads | {'yes' if check.get('loads') else 'no'} |")
    if simulation:
        lines.append(
            f"| {simulation['steps']} zero-control steps of {simulation['model']} | "
            f"{'finite' if simulation['finite'] else 'NOT finite'}, "
            f"{len(simulation['warnings'])} MuJoCo warnings |"
        )
    if kinematics:
        lines.append(
            f"| link poses at {kinematics['configurations']} configurations | max error "
            f"{kinematics['max_position_error']:.2g} m, "
            f"{kinematics['max_rotation_error']:.2g} rad; "
            f"{len(kinematics['missing_links'])} links missing |"
        )
    for prefix, part in sorted(check.get("parts", {}).items()):
        lines.append(
            f"| MJCF part {prefix} ({part['label']}) against the part alone, at "
            f"{part['configurations']} configurations | max error "
            f"{part['max_position_error']:.2g} m, {part['max_rotation_error']:.2g} rad; "
            f"{len(part['missing'])} missing, {len(part['problems'])} problems |"
        )
    actuation = check.get("actuation")
    if actuation is not None:
        lines.append(
            f"| every moving joint driven once | {check['actuation']['actuators']} actuators, "
            f"{len(actuation['problems'])} problems |"
        )
    if check.get("floor_gap") is not None:
        lines.append(f"| floating base on the floor at home | gap {check['floor_gap']:.2g} m |")
    hold = check.get("hold")
    if hold:
        where = f" ({hold['joint']})" if hold.get("joint") else ""
        tilt = hold.get("base_tilt")
        tilted = f"; the base tilted {tilt:.2g} rad" if tilt is not None else ""
        lines.append(
            f"| hold home's ctrl for 1 s | largest deviation {hold['max_deviation']:.3g}{where}"
            f"{tilted} |"
        )
    stand = check.get("stand")
    if stand:
        if stand.get("fell_without_controller"):
            lines.append(f"| stand at home for 5 s | fell: {stand['fell_without_controller']} |")
        elif stand.get("needs_controller"):
            lines.append(f"| stand at home for 5 s | not run: {stand['needs_controller']} |")
        else:
            lines.append(
                f"| stand at home holding its ctrl for {stand['seconds']:g} s | base tilted "
                f"{stand['max_tilt']:.2g} rad, sank {stand['max_sink'] * 1000:.0f} mm; largest "
                f"joint deviation {stand['max_deviation']:.3g} ({stand['joint']}) |"
            )
    menagerie = check.get("menagerie_test")
    if menagerie:
        lines.append(
            "| 1 s of pseudorandom control (Menagerie's model test) | "
            f"{'finite' if menagerie['finite'] else 'NOT finite'}, "
            f"{len(menagerie['warnings'])} MuJoCo warnings |"
        )
    joint_problems = len(check.get("joints", {}).get("problems", []))
    lines.append(f"| joint types, axes, ranges | {joint_problems} problems |")
    if masses:
        lines.append(
            f"| masses and inertias | total {masses['urdf_total']:.6g} kg in the URDF, "
            f"{masses['model_total']:.6g} kg in the model; {len(masses['problems'])} problems |"
        )
    lines.append("")
    contacts = check.get("resting_contacts", {})
    if contacts.get("pairs"):
        lines += ["### Robot bodies touching at home", ""]
        lines += [
            f"- {p['body1']} and {p['body2']} ({p['pose']} pose, {p['depth']:.3g} m deep)"
            for p in contacts["pairs"]
        ]
        lines += [
            "",
            "To let them be, add to the raw inputs:",
            "",
            "```xml",
            contacts["exclude"],
            "```",
            "",
        ]
    return lines + _runtime(check.get("mujoco_ros2_control")) + _gazebo(check.get("gazebo_sensors"))


def _motor(actuator: dict) -> str:
    """The motor behind an actuator (issue 33), if a rule named one."""
    from mjcfbuild.control.motors import URDF_LIMITS

    motor = actuator.get("motor")
    if not motor:
        return ""
    if motor["motor"] == URDF_LIMITS:
        return ", URDF speed line"
    return f", motor {motor['motor']}"


def _replaced(actuator: dict) -> str:
    """The placeholder effort an actuator's force range replaced, if any."""
    effort = actuator.get("placeholder_effort")
    return f" (URDF effort {effort:g}, a placeholder)" if effort else ""


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
                f"| {a['name']} | {a['joint']} | {a['type']} | {a['source']}{_motor(a)}"
                f"{', weight-bearing' if a.get('weight_bearing') else ''}"
                f"{_armature(a)} | "
                f"{_number(a.get('kp'))} | {_number(a.get('kv'))} | {_range(a.get('ctrlrange'))} "
                f"| {_range(a.get('forcerange'))}{_replaced(a)} |"
            )
    else:
        lines.append("None.")
    if readiness.get("passive"):
        lines += ["", "Passive joints (actuator type none): " + ", ".join(readiness["passive"])]
    lines += ["", "## Home pose", ""]
    if readiness.get("home"):
        lines += ["| joint | position | from |", "|---|---:|---|"]
        lines += [f"| {h['joint']} | {h['value']:.6g} | {h['source']} |" for h in readiness["home"]]
    if readiness.get("home_from"):
        what = "computed" if readiness["home_from"].startswith("crouch") else "srdf"
        lines += ["", f"The `{what}` values are the {readiness['home_from']}."]
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
                f"At home it stands on {', '.join(stance['feet'])}: they span "
                f"{stance['area'] * 1e4:.0f} cm2, its centre of mass "
                f"{stance['com_margin'] * 1000:.0f} mm inside their edge. Weight-bearing "
                "servos are stiffened to hold it (docs/simulation.md).",
            ]
        else:
            lines += ["", f"It cannot stand on its own: {stance['why_not']}."]
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
    shapes = ", ".join(f"{count} {kind}" for kind, count in sorted(kinds.items()))
    floor = ", ".join(training.get("floor", [])) or "none"
    lines = [
        "## Training variant",
        "",
        f"`{training['file']}`: collision shapes {shapes or 'none'}; floor contacts: {floor}; "
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
    lines += [f"- {note}" for note in training.get("notes", [])]
    warp = training.get("warp")
    if warp:
        full, variant = warp["full"], warp["variant"]
        lines += [
            "",
            f"In MuJoCo Warp ({variant['worlds']} worlds, {variant['steps']} steps with noise "
            f"on ctrl, `check --warp`): {warp['behaviour']}.",
            "",
            "| model | collision geoms | contact pairs | steps/s |",
            "|---|---:|---:|---:|",
        ]
        for name, row in (("full", full), ("variant", variant)):
            lines.append(
                f"| {name} | {row['collision_geoms']} | {row['contact_pairs']} "
                f"| {row['steps_per_second']:.0f} |"
            )
        lines += [f"- check failed: {failure}" for failure in warp.get("failures", [])]
        gpu = warp.get("gpu")
        if gpu and "error" in gpu:
            lines += ["", f"- check failed on the GPU: {gpu['error']}"]
        elif gpu:
            rows = (("full", gpu["full"]), ("variant", gpu["variant"]))
            lines += [
                "",
                f"On {gpu['device']} ({gpu['variant']['worlds']} worlds): {gpu['behaviour']}; "
                + ", ".join(f"{n} {r['steps_per_second']:.0f} steps/s" for n, r in rows)
                + ".",
            ]
            lines += [f"- check failed on the GPU: {failure}" for failure in gpu["failures"]]
    else:
        lines += ["", "Not yet measured in MuJoCo Warp: run `mjcfbuild check --warp`."]
    lines.append("")
    return lines


def _count(number: int, noun: str) -> str:
    """``1 iteration``, ``5 iterations``."""
    return f"{number} {noun}{'' if number == 1 else 's'}"


def _self_collision(matrix: dict | None) -> list[str]:
    """The collision matrix: every body pair that is excluded, with its reason."""
    if not matrix:
        return []
    pairs = matrix.get("pairs", [])
    excluded = [p for p in pairs if p["exclude"]]
    counts: dict[str, int] = {}
    for pair in pairs:
        counts[pair["reason"]] = counts.get(pair["reason"], 0) + 1
    summary = ", ".join(f"{count} {reason}" for reason, count in sorted(counts.items()))
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
            f"| {p['body1']} | {p['body2']} | {p['reason']} | "
            f"{'-' if p['reason'] == 'adjacent' else format(p['fraction'], '.0%')} |"
            for p in excluded
        ]
        lines.append("")
    return lines


def _number(value) -> str:
    return f"{value:.4g}" if value is not None else ""


def _range(values) -> str:
    return f"[{values[0]:.4g}, {values[1]:.4g}]" if values else ""


def _plausibility(report: dict) -> list[str]:
    """Where the meshes are: the plausibility test, COLLADA up axes, MJCF parts' own contacts."""
    check = report.get("check") or {}
    found = check.get("plausibility")
    decisions = report.get("up_axis") or []
    inside = (check.get("resting_contacts") or {}).get("inside_parts") or []
    if found is None and not decisions and not inside:
        return []
    lines = ["## Mesh plausibility", ""]
    if found is not None:
        findings = found.get("findings", [])
        lines.append(
            f"{found.get('bodies', 0)} bodies tested (centre of mass inside its own geometry, "
            f"visual and collision geometry overlapping): {len(findings) or 'none'} named."
        )
        lines.append("")
        if findings:
            lines += ["| body | result | problems | likely cause |", "|---|---|---|---|"]
            lines += [
                f"| {f['body']} | {'fails' if f['fails'] else 'warning'} | "
                f"{'; '.join(f['problems'])} | {f['detail']} |"
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
            f"| {d['mesh']} | {d.get('tag')} | {'yes' if d.get('turned') else 'no'} | "
            f"{d.get('reason')} |"
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
            f"- {p['body1']} and {p['body2']} in {p['part']} ({p['pose']} pose, "
            f"{p['depth']:.3g} m deep)"
            for p in inside
        ]
        lines.append("")
    return lines


def _armature(actuator: dict) -> str:
    """The armature the build gave a weight-bearing joint, if it did."""
    armature = actuator.get("armature")
    return f" (armature {armature:.3g} added)" if armature else ""


def _gazebo(sensors: list[dict] | None) -> list[str]:
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
        missing = "the sensor" if not sensor["modelled"] else ", ".join(sensor["not_modelled"])
        lines.append(
            f"| {sensor['name']} | {sensor['type']} | {sensor['reference']} | {missing or '-'} |"
        )
    return [*lines, ""]


def _runtime(runtime: dict | None) -> list[str]:
    """What mujoco_ros2_control finds for the <ros2_control> block (check.runtime)."""
    if not runtime:
        return []
    lines = ["### mujoco_ros2_control", ""]
    if runtime["joints"]:
        lines += [
            "| joint | command interfaces | actuator | kind (by its bias) |",
            "|---|---|---|---|",
        ]
        for joint in runtime["joints"]:
            how = ", ".join(
                f"{name}: {way or 'REFUSED'}" for name, way in joint["how"].items()
            ) or ", ".join(joint["interfaces"])
            lines.append(
                f"| {joint['joint']} | {how} | {joint['actuator'] or 'none'} | "
                f"{joint['kind'] or '-'} |"
            )
        lines.append("")
    if runtime["sensors"]:
        lines += ["| sensor | mujoco_type | MJCF sensors (site) |", "|---|---|---|"]
        for sensor in runtime["sensors"]:
            found = ", ".join(
                f"{m['type']} {m['name']}" + (f" ({m['site']})" if m["site"] else "")
                if m["found"]
                else f"{m['type']} {m['name']} MISSING"
                for m in sensor["mjcf"]
            )
            lines.append(f"| {sensor['sensor']} | {sensor['type']} | {found} |")
        lines.append("")
    for device in runtime["devices"]:
        rays = f", {device['rays']} rays" if device["kind"] == "lidar" else ""
        state = "found" if device["found"] else "MISSING"
        lines.append(f"- {device['kind']} {device['sensor']}: {state}{rays}")
    if runtime["devices"]:
        lines.append("")
    return lines
