"""Mass and inertia MuJoCo accepts: checked per body, repaired or refused by policy.

MuJoCo refuses a moving body whose mass or principal inertia is below its minimum, and any
body whose principal moments break the triangle inequality (A + B >= C). Real descriptions
ship dummy links with zero or singular inertia. Under the ``repair`` policy every such body is
fixed with the smallest change that makes it valid, and every change is reported (body,
before, after); under ``fail`` the build stops and names the body and the numbers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mjcfbuild.errors import InputError
from mjcfbuild.mjcf.bodies import Body, MassProperties
from mjcfbuild.numbers import output_list
from mjcfbuild.urdf.transforms import matrix3

TOLERANCE = 1e-12
# Repairs smaller than this (relative to the largest moment) are rounding, not defects: they are
# made silently, under either policy.
NOTICEABLE = 1e-6
# A + B is kept this much (relative to C) above C, so that writing the moments with 12
# significant digits cannot tip an exact equality (a flat plate) into MuJoCo's refusal.
TRIANGLE_MARGIN = 1e-9


@dataclass(frozen=True)
class InertiaPolicy:
    """What to do with masses and inertias MuJoCo would refuse."""

    mode: str = "repair"
    min_mass: float = 1e-4
    min_inertia: float = 1e-8
    # A link with geometry but no mass: "placeholder" (min_mass) or "geometry" (its geometry's
    # mass at ``density``, mjcf.geometry_mass), robot.yaml's inertia.missing.
    missing: str = "placeholder"
    density: float = 1000.0


@dataclass
class Repair:
    """One change made to a body's mass properties."""

    body: str
    problem: str
    before: str
    after: str
    where: str = ""  # file:line of the link's <inertial> (or the link), where known

    def describe(self) -> str:
        """One line for the build report."""
        at = f"{self.where}: " if self.where else ""
        return f"{at}body '{self.body}': {self.problem}; {self.before} -> {self.after}"


def validate_masses(
    bodies: list[Body],
    policy: InertiaPolicy,
    source: str,
    lines: dict[str, int | None],
    free_joint: tuple[str, str] = ("robot.yaml options.free_joint", "set free_joint: false"),
    from_geometry: str = "",
) -> list[Repair]:
    """Check (and under ``repair``, fix in place) every body's mass properties.
    ``free_joint`` names where the free joint was asked for (robot.yaml's, as ``LABEL
    KEY.PATH``, which the engine points at its line) and how not to ask: the cause when the
    floating base is the only body that moves. ``from_geometry`` says how to give links the
    masses of their geometry instead (robot.yaml's ``inertia.missing``), where that is not
    already asked for: a robot without a mass is refused with it."""
    other = f", or {from_geometry}" if from_geometry else ""
    repairs: list[Repair] = []
    total = sum(b.mass.mass for b in bodies if b.mass is not None and math.isfinite(b.mass.mass))
    moving = [body for body in bodies if body.moves]
    massless = all(b.mass is None or b.mass.mass == 0 for b in bodies)
    if massless and moving and all(body.floating for body in moving):
        # Nothing of the description moves: the free joint robot.yaml asked for made its
        # root a moving body (a static prop, a fixture), and that is what to change.
        where, turn_off = free_joint
        raise InputError(
            f"a free joint floats the robot, but no link of {source} has a mass (<inertial>), "
            f"so its floating base '{moving[0].name}' cannot be simulated",
            file=where,
            hint=f"{turn_off} for a robot that stays where it is, or add each link's "
            f"<inertial> (mass, centre of mass, inertia) to {source}{other}",
        )
    if moving and massless:
        # Every body would get the smallest placeholder mass: servos sized for 0.1 g links go
        # unstable and nothing about the model's dynamics is the robot's.
        raise InputError(
            f"no link of the robot has a mass (<inertial>), so its {len(moving)} moving "
            f"{'body cannot' if len(moving) == 1 else 'bodies cannot'} be simulated",
            file=source,
            hint="add each link's <inertial> (mass, centre of mass, inertia) to the "
            f"description: MuJoCo needs them to simulate it{other}",
        )
    for body in bodies:
        if body.name == "world" and body.parent is None:
            continue
        if body.floating and (body.mass is None or body.mass.mass < policy.min_mass):
            repairs += _floating_root(body, policy, total, source, lines)
        if body.mass is not None and (not math.isfinite(body.mass.mass) or body.mass.mass < 0):
            raise InputError(
                f"link '{body.name}' has mass {body.mass.mass}; a mass must be a number >= 0",
                file=source,
                line=lines.get(body.name),
            )
        for problem, before, after, fixed, noticeable in _problems(body, policy):
            if not noticeable:
                body.mass = fixed
                continue
            if policy.mode != "repair":
                raise InputError(
                    f"link '{body.name}': {problem} ({before})",
                    file=source,
                    line=lines.get(body.name),
                    hint="fix the <inertial>, or set inertia.policy: repair in robot.yaml",
                )
            body.mass = fixed
            line = lines.get(body.name)
            where = f"{source}:{line}" if line else ""
            repairs.append(Repair(body.name, problem, before, after, where))
    return repairs


# A massless floating root gets this share of the robot's mass, as a solid sphere of
# FLOATING_RADIUS: the smallest mass keeps its own inertia so far below the limbs it carries
# that random control makes the simulation unstable.
FLOATING_SHARE = 0.01
FLOATING_RADIUS = 0.05


def _floating_root(
    body: Body, policy: InertiaPolicy, total: float, source: str, lines: dict
) -> list[Repair]:
    before = "no <inertial>" if body.mass is None else f"mass {body.mass.mass:g}"
    if policy.mode != "repair":
        raise InputError(
            f"link '{body.name}' floats (options.free_joint) but has {before}",
            file=source,
            line=lines.get(body.name),
            hint="give it an <inertial>, or set inertia.policy: repair in robot.yaml",
        )
    mass = max(policy.min_mass, FLOATING_SHARE * total)
    moment = 0.4 * mass * FLOATING_RADIUS**2
    body.mass = MassProperties(
        mass=mass,
        com=body.mass.com if body.mass is not None else (0.0, 0.0, 0.0),
        inertia=((moment, 0.0, 0.0), (0.0, moment, 0.0), (0.0, 0.0, moment)),
        links=body.mass.links if body.mass is not None else [],
    )
    after = f"mass {mass:.4g} (1% of the robot), inertia {moment:.3g}"
    line = lines.get(body.name)
    where = f"{source}:{line}" if line else ""
    return [Repair(body.name, "floating root without mass", before, after, where)]


def _problems(body: Body, policy: InertiaPolicy):
    """Yield (problem, before, after, repaired properties, noticeable) for each defect of
    ``body``."""
    import numpy as np

    mass = body.mass
    if body.moves and (mass is None or mass.mass < policy.min_mass):
        before = "no <inertial>" if mass is None else f"mass {mass.mass:g}"
        fixed = MassProperties(
            mass=policy.min_mass,
            com=mass.com if mass is not None else (0.0, 0.0, 0.0),
            inertia=mass.inertia if mass is not None else ((0.0,) * 3,) * 3,
            links=mass.links if mass is not None else [],
        )
        yield "moving body with too small a mass", before, f"mass {policy.min_mass:g}", fixed, True
        mass = fixed
    if mass is None:
        return
    tensor = np.array(mass.inertia, dtype=float)
    tensor = 0.5 * (tensor + tensor.T)
    moments, axes = np.linalg.eigh(tensor)
    floor = policy.min_inertia if body.moves else 0.0
    repaired = np.maximum(moments, floor)
    scale = max(1.0, float(np.max(np.abs(moments))))
    order = np.argsort(repaired)
    a, b, c = (repaired[i] for i in order)
    deficit = c - a - b + TRIANGLE_MARGIN * c
    if c > 0 and deficit > 0:
        repaired[order[0]] += deficit / 2.0
        repaired[order[1]] += deficit / 2.0
    if np.array_equal(repaired, moments):
        return
    magnitude = max(float(np.max(np.abs(moments))), floor)
    noticeable = not np.allclose(repaired, moments, rtol=0.0, atol=NOTICEABLE * magnitude)
    if np.any(moments < -TOLERANCE * scale):
        problem = "inertia is not positive definite"
    elif body.moves and np.any(moments < floor):
        problem = "principal inertia too small for a moving body"
    else:
        problem = "principal inertia breaks A + B >= C"
    new_tensor = axes @ np.diag(repaired) @ axes.T
    fixed = MassProperties(
        mass=mass.mass,
        com=mass.com,
        inertia=matrix3((float(v) for v in row) for row in new_tensor),
        links=mass.links,
    )
    yield (
        problem,
        f"principal moments {output_list(sorted(moments))}",
        f"{output_list(sorted(repaired))}",
        fixed,
        noticeable,
    )
