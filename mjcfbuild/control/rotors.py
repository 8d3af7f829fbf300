"""Telling a torque-speed line's rotor that no real drive of the joint could have.

A position servo with the URDF's effort and velocity as its torque-speed line gets the rotor
inertia (armature) that keeps the line stable: timestep x effort / velocity
(``motors.line_inertia``). Geared drives really do outweigh what they move - wrists and
fingers, where the reflected rotor is tens to hundreds of times the most inertia the moved
links could have (UR and panda wrists, allegro's, inspire's and the Interbotix grippers'
fingers: at most about 400 over the robots built) - so that alone says nothing. Placeholder
limits do say it: a 3.1 g hand whose joints all say 1000 N m got 0.2 kg m^2 on each joint (2
where the velocity is 1 rad/s), 25000 times what its fingers could have, and moved like a
flywheel under any contact (robotiq's 1000 N m finger: 2500 times; schunk svh's: 27000).
Past :data:`ROTOR_RATIO` the build warns, naming the limits and what to set instead.
"""

from __future__ import annotations

from dataclasses import dataclass

from mjcfbuild.control.efforts import subtree

# An armature this many times the most inertia the joint moves is no real drive's (real robots'
# URDF lines: at most about 400; placeholder limits: 2500 and more).
ROTOR_RATIO = 1000.0


@dataclass(frozen=True)
class HeavyRotor:
    """A joint whose speed line's armature dwarfs what it moves."""

    joint: str
    armature: float  # kg m^2 (a slide's: kg)
    bound: float  # the most inertia the joint moves could have (kg m^2; a slide's: kg)
    mass: float  # kg, what the joint moves
    reach: float  # m, the farthest its geometry reaches from the axis (0 for a slide)
    slide: bool


def heavy_rotor(model, data, joint: str, armature: float, moved: float) -> HeavyRotor | None:
    """The finding for ``joint``'s speed-line ``armature`` in ``data``'s pose, where it exceeds
    :data:`ROTOR_RATIO` times the most inertia the joint moves: the mass of its bodies at the
    farthest their geometry reaches from the axis (a slide: that mass), or ``moved`` (the
    inertia its servo was sized for, mimic followers included) where that is more."""
    import mujoco
    import numpy as np

    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
    if index < 0:
        return None
    moving = subtree(model, int(model.jnt_bodyid[index]))
    mass = float(sum(model.body_mass[body] for body in moving))
    slide = model.jnt_type[index] == mujoco.mjtJoint.mjJNT_SLIDE
    reach = 0.0
    if not slide:
        anchor, axis = data.xanchor[index], data.xaxis[index]
        # Each body's centre of mass, and each geom's bounding sphere: a link's matter lies
        # within its geometry, and a roll joint's centres of mass lie on its axis.
        points = [(data.xipos[body], 0.0) for body in moving]
        points += [
            (data.geom_xpos[geom], float(model.geom_rbound[geom]))
            for geom in range(model.ngeom)
            if model.geom_bodyid[geom] in moving
        ]
        reach = max(float(np.linalg.norm(np.cross(p - anchor, axis))) + r for p, r in points)
    bound = max(mass if slide else mass * reach**2, moved)
    if not armature > ROTOR_RATIO * bound:
        return None
    return HeavyRotor(joint, armature, bound, mass, reach, bool(slide))


def describe(
    found: HeavyRotor,
    where: str,
    effort: float,
    velocity: float,
    rule: str | None = None,
    shared: bool = False,
) -> str:
    """The build's warning about ``found``, at ``where`` (the joint's URDF file and line), whose
    line runs from ``effort`` to ``velocity``. ``rule`` is where robot.yaml gives the effort
    (``robot.yaml:5: actuators.rules[0].forcerange``) when an actuators rule's forcerange, not
    the URDF, gave it; ``shared`` that this rule drives other joints too."""
    unit, force, speed = ("kg", "N", "m/s") if found.slide else ("kg m^2", "N m", "rad/s")
    links = f"its {found.mass:.3g} kg of links"
    most = links if found.slide else f"{links} at up to {found.reach:.3g} m from the axis"
    own_rule = f'{{joints: ["{found.joint}"], forcerange: [-E, E]}}'
    if rule is None:
        limits = f"its URDF limits (effort {effort:g} {force}, velocity {velocity:g} {speed})"
        fix = (
            "give the joint its real effort and velocity in the URDF, or its real effort E in "
            f"robot.yaml: actuators: {{rules: [{own_rule}]}}"
        )
    else:
        limits = (
            f"its effort {effort:g} {force} (from {rule}) and URDF velocity {velocity:g} {speed}"
        )
        fix = (
            (
                f"give the joint its real effort E in a rule of its own before that one "
                f"({own_rule}: the first rule matching a joint applies)"
            )
            if shared
            else "give the joint its real effort E in that rule (forcerange: [-E, E])"
        ) + ", and its real velocity in the URDF"
    return (
        f"{where}: joint '{found.joint}': {limits} give it a rotor inertia (armature) of "
        f"{found.armature:.3g} {unit}, {found.armature / found.bound:,.0f} times the most "
        f"{most} could have ({found.bound:.3g} {unit}): no real drive is that heavy, so the "
        f"limits (or the links' masses) look like placeholders; {fix}"
    )
