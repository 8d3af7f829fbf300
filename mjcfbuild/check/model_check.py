"""``mjcfbuild check``: prove a built model against its URDF, and say exactly what is wrong.

Checks, each independent of MuJoCo's own URDF import: the model loads; 2,000 zero-control
steps stay finite and raise no MuJoCo warning; every URDF link (body or site of its name) sits
where the URDF's forward kinematics puts it at random joint configurations; joint types, axes
and ranges match; masses, centres of mass and inertias match, except for bodies whose inertia
the build reported repairing; no two robot bodies touch at home (the pairs are listed with a
ready contact exclude); and the model is ready to control (see mjcfbuild.check.control).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from mjcfbuild.check.contacts import exclude_suggestion, resting_contacts, split_by_part
from mjcfbuild.check.control import check_control, menagerie_test, outside_at_qpos0
from mjcfbuild.check.findings import Problem, structural_first
from mjcfbuild.check.joints import compare_joints
from mjcfbuild.check.kinematics import compare_kinematics
from mjcfbuild.check.loading import AssetSource, compile_model
from mjcfbuild.check.masses import compare_masses, placeholder_bodies, urdf_mass
from mjcfbuild.check.meshstats import mesh_statistics
from mjcfbuild.check.precision import relative_tolerance
from mjcfbuild.check.reference import reference_from_record
from mjcfbuild.check.results import (
    CheckResults,
    Joints,
    Kinematics,
    Masses,
    MeshStatistics,
    PartContact,
    PlausibilityResults,
    RestingContacts,
    Simulation,
)
from mjcfbuild.check.simulation import simulate
from mjcfbuild.mjcf.geometry_mass import GeometryMass, with_given
from mjcfbuild.mjerrors import load_error
from mjcfbuild.mjsensors import without_sensors
from mjcfbuild.mjstopped import SimulationStopped, simulating
from mjcfbuild.urdf.model import Robot


@dataclass(frozen=True)
class CheckOptions:
    """Tolerances and sample sizes of the check."""

    configurations: int = 20
    seed: int = 0
    position_tolerance: float = 1e-6
    rotation_tolerance: float = 1e-6
    steps: int = 2000
    hold_tolerance: float = 0.05
    # Axes, ranges, masses, inertias; None: 1e-6, or coarser as the model's digits require.
    relative_tolerance: float | None = None


def check_model(
    robot: Robot,
    model_path: Path,
    simulate_path: Path | None = None,
    repaired: set[str] | None = None,
    options: CheckOptions | None = None,
    readiness: dict | None = None,
    reference: dict | None = None,
    sources: dict[str, AssetSource] | None = None,
    part_bodies: dict[str, set[str]] | None = None,
    geometry_masses: list[GeometryMass] | None = None,
) -> CheckResults:
    """Check the model at ``model_path`` against ``robot``; simulate ``simulate_path`` (the
    scene, with its floor) or the model itself. ``readiness`` is what the build recorded about
    actuators and home (None for a model mjcfbuild did not build: undriven joints are then
    reported, not failures). ``reference``, what an independent reader read from the URDF text
    (:func:`~mjcfbuild.check.reference.read_kinematics`), gives the reference kinematics;
    ``robot`` names links and lines in messages. ``sources``, the
    products a build published the assets from, make loading faster (see check.loading).
    ``part_bodies``: each MJCF part's bodies, by the part's name; contacts at rest inside one
    part are reported, not failures. ``geometry_masses``: the masses the build gave links
    without one from their geometry (robot.yaml's ``inertia.missing: geometry``), which the
    model's masses are compared with as if the URDF gave them, and which the results name."""

    from mjcfbuild.mjwarnings import capture_mujoco_warnings

    capture_mujoco_warnings()  # simulation warnings are read from MjData instead
    options = options or CheckOptions()
    # The scene includes the model, so one load serves every check (meshes load once).
    path = simulate_path or model_path
    try:
        model = without_sensors(compile_model(path, sources))
    except Exception as exc:
        line = f"{path.name} does not load: {load_error(exc)}"
        return CheckResults(loads=False, failures=[line])
    results = CheckResults(loads=True)
    problems: list[Problem] = []
    try:
        with simulating(f"{options.steps} zero-control steps of {path.name}"):
            simulation = simulate(model, options.steps)
    except SimulationStopped as stop:
        problems.append(Problem(stop.line))
        results = results.add(
            simulation=Simulation(path.name, options.steps, False, [], stopped=stop.line)
        )
    else:
        results = results.add(
            simulation=Simulation(
                path.name, simulation.steps, simulation.finite, simulation.warnings
            )
        )
        if not simulation.finite:
            problems.append(
                Problem(f"the state is not finite within {options.steps} zero-control steps")
            )
        for warning in simulation.warnings:
            problems.append(Problem(f"MuJoCo warned while simulating: {warning}"))

    reader, fallback = reference_from_record(reference)
    kinematics = compare_kinematics(robot, model, options.configurations, options.seed, reader)
    tolerances = (options.position_tolerance, options.rotation_tolerance)
    first = kinematics.first_wrong(*tolerances)
    results = results.add(
        kinematics=Kinematics(
            configurations=options.configurations,
            max_position_error=kinematics.max_position,
            max_rotation_error=kinematics.max_rotation,
            worst_link=kinematics.worst.link if kinematics.worst else None,
            missing_links=kinematics.missing_links,
            missing_joints=kinematics.missing_joints,
            reference=reader.name if reader else f"mjcfbuild's URDF parser: {fallback}",
            failed=first is not None or bool(kinematics.missing_links),
        )
    )
    for link in kinematics.missing_links:
        problems.append(
            Problem(f"link '{link}' has no body or site of its name in the model", True)
        )
    if first is not None:
        others = kinematics.wrong_count(*tolerances) - 1
        problems.append(
            Problem(
                f"link '{first.link}' is {first.position:.3g} m and {first.rotation:.3g} rad "
                f"from its URDF pose at configuration {first.configuration} (tolerances "
                f"{options.position_tolerance:g} m, {options.rotation_tolerance:g} rad)"
                + (f"; {others} links below it follow" if others > 0 else "")
            )
        )

    relative = relative_tolerance(model_path, options.relative_tolerance)
    joint_problems = compare_joints(robot, model, relative)
    results = results.add(joints=Joints([p.text for p in joint_problems], relative))
    problems += joint_problems

    given = geometry_masses or []
    weighed = with_given(robot, given)  # the masses the model should have
    mass_problems, _, model_mass = compare_masses(weighed, model, repaired or set(), relative)
    results = results.add(
        masses=Masses(
            urdf_total=urdf_mass(robot),
            model_total=model_mass,
            problems=[p.text for p in mass_problems],
            repaired_bodies=sorted(repaired or ()),
            placeholder_bodies=placeholder_bodies(weighed, model),
            from_geometry=[record.link for record in given],
            geometry_total=sum(record.mass for record in given),
            geometry_density=given[0].density if given else 0.0,
        )
    )
    problems += mass_problems
    results = results.add(structural_first(problems))

    try:
        with simulating("the contacts at home"):
            at_rest = resting_contacts(model)
    except SimulationStopped as stop:
        results = results.add([stop.line])
        at_rest = []
    contacts, in_parts = split_by_part(at_rest, part_bodies or {})
    results = results.add(
        resting_contacts=RestingContacts(
            pairs=contacts,
            exclude=exclude_suggestion(contacts),
            inside_parts=[PartContact(part, **c.__dict__) for part, c in in_parts],
        )
    )
    if contacts:
        listed = ", ".join(f"{c.body1}/{c.body2}" for c in contacts[:5])
        more = f" and {len(contacts) - 5} more" if len(contacts) > 5 else ""
        results = results.add(
            [
                f"{len(contacts)} robot body pair{'s' if len(contacts) > 1 else ''} touch at "
                f"{contacts[0].pose} ({listed}{more}); exclude them (report.md has the block) "
                "or fix the collision geometry"
            ]
        )

    passive = set((readiness or {}).get("passive", []))
    top_speeds: dict[str, float] = {}
    try:
        with simulating("the control checks"):  # each simulation there says which it was
            control = check_control(
                model, passive, options.hold_tolerance, readiness is not None, results
            )
    except SimulationStopped as stop:
        results = results.add([stop.line])
    else:
        results, top_speeds = control.results, control.top_speeds
    results = _speed_bound(results, top_speeds, robot, model, readiness)  # issue 33
    results = results.add(meshes=[MeshStatistics(**row) for row in mesh_statistics(model)])
    try:
        with simulating("the plausibility checks"):
            results = _check_plausibility(model, results, sources, weighed, repaired or set())
    except SimulationStopped as stop:
        results = results.add([stop.line])
    return results


def _check_plausibility(
    model,
    results: CheckResults,
    sources: dict[str, AssetSource] | None,
    robot: Robot,
    repaired: set[str],
) -> CheckResults:
    """Centres of mass inside their bodies' geometry, visual and collision overlapping, masses
    their geometry can hold (check.plausibility): meshes in mm and masses in the wrong unit
    fail; other findings are warnings in the results. Bodies whose mass or inertia the build
    repaired (a zero mass made the smallest MuJoCo accepts) are not judged: the repair is
    reported where it was made."""
    from mjcfbuild.check.plausibility import check_plausibility

    found = check_plausibility(model, sources, skip=repaired, robot=robot)
    section = PlausibilityResults(found.bodies, found.findings, found.failures, found.warnings)
    return results.add(found.failures, plausibility=section)


def _speed_bound(
    results: CheckResults,
    tops: dict[str, float],
    robot: Robot,
    model,
    readiness: dict | None,
) -> CheckResults:
    """The Menagerie test's speed bound (check.speeds): the joint fastest against its velocity
    limit, and a failure for every joint past its bound."""
    import mujoco

    from mjcfbuild.check.speeds import joint_speeds, speed_results

    limits = {
        joint.name: (joint.limit.velocity if joint.limit is not None else None)
        for joint in robot.joints
    }
    kinds = {}
    for index in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, index)
        slide = model.jnt_type[index] == mujoco.mjtJoint.mjJNT_SLIDE
        kinds[name] = "slide" if slide else "hinge"
    actuators = (readiness or {}).get("actuators", [])
    speeds = joint_speeds(tops, limits, kinds, actuators)
    start = ""
    outside, clipped = outside_at_qpos0(model)
    if outside and any(speed.fails for speed in speeds):
        # The test starts at qpos0 (zero): a joint whose range leaves out zero is thrown back
        # by its limit and throws its neighbours, faster than any servo (jaco's elbow at
        # 70 times its limit, still at 1 time from inside its range). Measured again from
        # inside the ranges, the speeds are the servos'.
        try:
            with simulating("1 s of pseudorandom control from inside the joint ranges"):
                again = menagerie_test(model, clipped)
        except SimulationStopped as stop:
            return results.add([stop.line])
        speeds = joint_speeds(again.top_speeds, limits, kinds, actuators)
        shown = ", ".join(outside[:3]) + (
            f" and {len(outside) - 3} more" if len(outside) > 3 else ""
        )
        start = f"qpos0 clipped into the joint ranges ({shown} outside at qpos0)"
    bound, failures = speed_results(speeds, start)
    return results.add(failures, speeds=bound)
