"""The plausibility test's judgement of masses: each body's mass against the volume of its own
geometry (check.density), the robot's total mass against all of it, and the links welded to
the world, whose masses and inertias MuJoCo drops without a word.

A body ten times denser than tungsten or ten times lighter than foam fails the check with the
likely cause (a mass in grams or tonnes, a missing mesh scale); nearer the bounds it is a
warning (a collision primitive larger than the part, a placeholder mass, ballast). Each is
named at the URDF link to fix when the URDF is known. Links welded to the world do not move, so
their findings are warnings: the model simulates the same, the description is still wrong.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mjcfbuild.check.density import (
    HIGH_DENSITY,
    Volume,
    body_volumes,
    density_cause,
    density_fails,
    density_problem,
)
from mjcfbuild.check.findings import BodyFinding
from mjcfbuild.check.masses import owner_bodies
from mjcfbuild.urdf.model import Robot

if TYPE_CHECKING:
    import mujoco

# A principal moment may break A + B >= C by this much of C (rounding in the description).
TRIANGLE_SLACK = 1e-6
# The mass of a body lies within its geometry's reach of its centre of mass, so its radius of
# gyration cannot exceed that reach; this many times beyond it, the geometry is only a marker.
MARKER_REACH = 2.0
# Geometry whose largest geom fits in a sphere this small (m) is a marker: no robot part is.
MARKER_SIZE = 0.005


def mass_findings(
    model: mujoco.MjModel, robot: Robot | None, min_mass: float, skip: set[str]
) -> list[BodyFinding]:
    """The findings on the masses of ``model``; ``robot``, its URDF, names the link
    and line of each finding and gives the masses of links welded to the world."""
    import mujoco

    volumes = body_volumes(model)
    links_of: dict[int, list[str]] = {}
    if robot is not None:
        for link, body in owner_bodies(robot, model).items():
            links_of.setdefault(body, []).append(link)
    findings: list[BodyFinding] = []
    total_mass, total = 0.0, Volume(0.0, 0.0)
    for body, volume in sorted(volumes.items()):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or f"body {body}"
        mass = float(model.body_mass[body])
        if body == 0:
            if robot is None:
                continue
            mass = _urdf_mass(robot, links_of.get(0, []))
        problem = density_problem(mass, volume)
        if name in skip or (
            problem and problem[1] > HIGH_DENSITY and body != 0 and _marker(model, body)
        ):
            continue
        welded = int(model.body_weldid[body]) == 0  # static: MuJoCo never moves its mass
        if not welded:
            # The whole robot counts the light bodies too: a hand in tonnes has each finger
            # below the lightest body judged alone.
            total_mass += mass
            total = Volume(total.low + volume.low, total.high + volume.high)
        if mass < min_mass or problem is None:
            continue
        text, density = problem
        where, links = _where(robot, links_of.get(body, []))
        if body == 0:
            text += f" (links welded to the world: {', '.join(links)}; MuJoCo ignores their mass)"
        elif welded:
            text += " (welded to the world: MuJoCo ignores its mass)"
        elif links and links[0] != name:
            text += f" (link '{links[0]}' carries most of it)"
        fails = not welded and density_fails(density)
        cause = density_cause(density)
        markers = _massless_with_geometry(robot, links) if density < HIGH_DENSITY else []
        marker = robot.link(markers[0]) if robot is not None and markers else None
        at = f" (line {marker.line})" if marker is not None and marker.line else ""
        decides = _marker_decides(robot, markers, volume) if markers else False
        if decides is None:
            # A part drawn with a mesh and given no <inertial>: the body weighs only what its
            # other links give it (a tool's gram on a wrist), which no unit explains.
            several = len(markers) > 1
            named = ", ".join(f"'{link}'" for link in markers[:3]) + ("" if several else at)
            cause = (
                f"{'links' if several else 'link'} {named} "
                f"{'have' if several else 'has'} geometry but no mass in the URDF (no "
                "<inertial>): the body weighs only what its other links give it; give "
                f"{'them their' if several else 'it its'} <inertial>"
            )
        elif decides:
            # A massless link fused into the body (a gunsight, a sensor's field of view)
            # adds volume that holds none of the mass: too light is then no proof of a unit.
            cause = (
                f"link '{markers[0]}'{at} adds geometry with no mass (a marker, a sensor's "
                "field of view), whose volume is not the part's: give it a mass, or leave the "
                "warning"
            )
            fails = False
        findings.append(BodyFinding(name, [text], "mass units", cause, fails, where=where))
    # Mass on moving bodies without geometry weighs too.
    total_mass += sum(
        float(model.body_mass[b])
        for b in range(1, model.nbody)
        if b not in volumes and model.body_weldid[b] != 0
    )
    if not findings and total_mass > 0:
        findings += _total_finding(model, robot, total_mass, total)
    if robot is not None:
        findings += _world_inertias(robot, links_of.get(0, []))
    return findings


def _marker(model: mujoco.MjModel, body: int) -> bool:
    """Whether ``body``'s geometry is a marker, not the part: none of it is a centimetre
    across (the invisible 1 mm spheres of "fake" links), or its inertia puts the mass further
    from the centre of mass than any of it reaches (a 1 mm sphere on a link whose inertia says
    15 cm, written "to stabilize simulation"). Nothing about the mass can be told from such
    geometry."""
    import numpy as np

    mass = float(model.body_mass[body])
    gyration = float(np.sqrt(np.max(model.body_inertia[body]) / mass))
    geoms = np.flatnonzero(model.geom_bodyid == body)
    offsets = np.linalg.norm(model.geom_pos[geoms] - model.body_ipos[body], axis=1)
    reach = float(np.max(offsets + model.geom_rbound[geoms]))
    size = float(np.max(model.geom_rbound[geoms]))
    return size < MARKER_SIZE or gyration > MARKER_REACH * reach


def _massless_with_geometry(robot: Robot | None, links: list[str]) -> list[str]:
    """Those of ``links`` that carry geometry but no mass (no ``<inertial>``, or mass 0)."""
    if robot is None:
        return []
    found = []
    for name in links:
        link = robot.link(name)
        if link.shapes and (link.inertial is None or link.inertial.mass <= 0):
            found.append(name)
    return found


def _marker_decides(robot: Robot | None, markers: list[str], volume: Volume) -> bool | None:
    """Whether the geometry of the massless ``markers`` is what makes the body look too light:
    the largest volume one of their primitives holds reaches the body's lower bound. None where
    one is drawn with a mesh, whose volume the URDF does not tell: it never turns a failure
    into a warning (a massless camera mesh must not hide a mass in tonnes), but the cause is
    then as likely the link without a mass as a unit."""
    import math

    if robot is None:
        return False
    meshes = False
    largest = 0.0
    for name in markers:
        for shape in robot.link(name).shapes:
            size = shape.geometry.size
            kind = shape.geometry.kind
            if kind == "box" and len(size) == 3:
                largest = max(largest, size[0] * size[1] * size[2])
            elif kind == "cylinder" and len(size) == 2:
                largest = max(largest, math.pi * size[0] ** 2 * size[1])
            elif kind == "sphere" and size:
                largest = max(largest, 4.0 / 3.0 * math.pi * size[0] ** 3)
            elif kind == "capsule" and len(size) == 2:
                radius, length = size
                largest = max(largest, math.pi * radius**2 * (length + 4.0 / 3.0 * radius))
            else:
                meshes = True
    if largest >= volume.low * (1.0 - 1e-6):
        return True
    return None if meshes else False


def _urdf_mass(robot: Robot, links: list[str]) -> float:
    inertials = [robot.link(link).inertial for link in links]
    return sum(inertial.mass for inertial in inertials if inertial is not None)


def _where(robot: Robot | None, links: list[str]) -> tuple[str, list[str]]:
    """("file:line" of the heaviest of ``links``, the links heaviest first)."""
    if robot is None or not links:
        return "", links

    def mass(name: str) -> float:
        inertial = robot.link(name).inertial
        return inertial.mass if inertial is not None else 0.0

    ordered = sorted(links, key=lambda name: (-mass(name), name))
    line = robot.link(ordered[0]).line
    return (f"{robot.source}:{line}" if line else robot.source), ordered


def _total_finding(
    model: mujoco.MjModel, robot: Robot | None, mass: float, volume: Volume
) -> list[BodyFinding]:
    """The robot's total mass against all its geometry: catches mass on bodies without
    geometry, and bodies each too light to be judged alone."""
    problem = density_problem(mass, volume)
    if problem is None:
        return []
    text, density = problem
    name = robot.name if robot is not None else "model"
    where = robot.source if robot is not None else ""
    text = "in all: " + text
    fails = density_fails(density)
    return [BodyFinding(name, [text], "mass units", density_cause(density), fails, where, "robot")]


def _world_inertias(robot: Robot, links: list[str]) -> list[BodyFinding]:
    """Links welded to the world whose mass or inertia no body could have: MuJoCo drops the
    world's mass properties, so nothing else reports them."""
    import numpy as np

    findings = []
    for name in sorted(links):
        link = robot.link(name)
        inertial = link.inertial
        if inertial is None:
            continue
        ixx, ixy, ixz, iyy, iyz, izz = inertial.inertia
        tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)
        if not np.all(np.isfinite(tensor)) or not np.isfinite(inertial.mass):
            problem = "its mass or inertia is not a number"
        elif inertial.mass < 0:
            problem = f"its mass {inertial.mass:g} is negative"
        else:
            a, b, c = sorted(float(v) for v in np.linalg.eigvalsh(tensor))
            scale = max(abs(c), 1e-300)
            if a < -TRIANGLE_SLACK * scale:
                problem = f"its inertia is not positive definite (principal moments {a:.3g}, "
                problem += f"{b:.3g}, {c:.3g})"
            elif c - a - b > TRIANGLE_SLACK * scale:
                problem = f"its principal moments {a:.3g}, {b:.3g}, {c:.3g} break A + B >= C"
            else:
                continue
        line = inertial.line or link.line
        findings.append(
            BodyFinding(
                name,
                [problem + " (welded to the world: MuJoCo ignores it)"],
                "impossible inertia",
                "a wrong <inertial>: no body has these mass properties; fix them (they "
                "matter once the link moves or the description is used elsewhere)",
                False,
                f"{robot.source}:{line}" if line else robot.source,
                "link",
            )
        )
    return findings
