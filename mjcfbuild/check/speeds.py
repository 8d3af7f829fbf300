"""The speed bound of the model test: how fast each joint went under MuJoCo Menagerie's
pseudorandom control, against the speed the real joint can reach.

A joint's limit is its URDF ``<limit velocity>``; where the URDF gives none (or a placeholder:
0, -1, or :data:`PLACEHOLDER_SPEED` and above, as 1e9 is written for "no limit"), the no-load
speed of the motor that drives it, else :data:`DEFAULT_LIMIT` (rad/s, or m/s for a slide). How
far past it a joint may go depends on what the model knows:

- a joint driven by a motor with a torque-speed line (``motors:``) cannot drive itself past the
  line's no-load speed; only what moves it from outside (its neighbours, a falling base) can,
  so it fails past :data:`DRIVEN_MULTIPLE` times its limit;
- a joint whose servo has no speed limit (no motor data) or only the line the URDF's effort and
  velocity limits draw (issue 30) fails past :data:`FREE_MULTIPLE` times its limit: servos
  without a line, thrown across their range by the test's pseudorandom commands, reach 3-11
  times the velocity limits of the real arms and legs of docs/robots.md and up to 37 times
  those of grippers and lifts (talos's fingers: 1 rad/s), while a runaway servo (a
  placeholder effort, a nearly massless body) reaches hundreds of times its limit. A joint
  that starts the test outside its range (qpos0 is zero) is thrown back by the limit; where
  that throws a joint past its bound, the check measures again from inside the ranges.
  Past 1 time its limit a joint is listed in check.json's ``speed_bound``, not failed.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mjcfbuild.check.results import Speeds

DRIVEN_MULTIPLE = 1.5
FREE_MULTIPLE = 50.0
DEFAULT_LIMIT = {"hinge": 100.0, "slide": 10.0}  # rad/s, m/s: joints with no limit anywhere
# A URDF velocity limit this high (rad/s or m/s) stands for "no limit": no motor turns at nearly ten
# million rpm (descriptions write 1e8, 1e9 or 1e16), and held to it, a runaway would never fail.
PLACEHOLDER_SPEED = 1e6


@dataclass(frozen=True)
class JointSpeed:
    """One joint's top speed under the test and the bound it is held to."""

    joint: str
    speed: float
    limit: float
    limit_from: str  # urdf, motor or default
    multiple: float  # how many times the limit it may reach before the check fails
    unit: str = "rad/s"  # m/s for a slide
    unlimited: bool = False  # its servo has no force limit (the URDF gives no effort)

    @property
    def exceeds_limit(self) -> bool:
        """Faster than the real joint's limit."""
        return self.speed > self.limit

    @property
    def fails(self) -> bool:
        """Past the bound."""
        return self.speed > self.multiple * self.limit

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)


def _real_speed(limit: float) -> bool:
    """Whether ``limit`` is a velocity limit, not a placeholder for none."""
    return 0 < limit < PLACEHOLDER_SPEED


def joint_speeds(
    top_speeds: dict[str, float],
    urdf_limits: dict[str, float | None],
    kinds: dict[str, str],
    actuators: list[dict],
) -> list[JointSpeed]:
    """The bound of every joint in ``top_speeds`` (joint -> top speed): ``urdf_limits`` are the
    URDF's velocity limits, ``kinds`` the joints' types (hinge or slide), ``actuators`` the
    assembly's actuator records (with their ``motor``)."""
    from mjcfbuild.control.motors import URDF_LIMITS

    drives = {
        record["joint"]: record["motor"]
        for record in actuators
        if record.get("motor") and record["motor"].get("no_load_speed")
    }
    # A line drawn from the URDF's own limits stops the drive there too, but a default model
    # starts the test at qpos0, which may lie outside a joint's range (a knee bent one way):
    # the limit throws such a joint back faster than its line allows, so it keeps the free bound.
    named = {joint for joint, motor in drives.items() if motor.get("motor") != URDF_LIMITS}
    # Only a servo the build made says so by its record: the user's own (or a part's) may be
    # limited by its joint's actuatorfrcrange, which the URDF's effort gives.
    unlimited = {
        record["joint"]
        for record in actuators
        if record.get("type") == "position"
        and not record.get("forcerange")
        and record.get("source") not in ("user", "part")
    }
    result = []
    for joint, speed in sorted(top_speeds.items()):
        given = urdf_limits.get(joint)
        # A line drawn from the URDF's limits has the URDF's placeholder as its no-load speed.
        drive = float(drives[joint]["no_load_speed"]) if joint in drives else None
        if given is not None and _real_speed(given):
            limit, source = given, "urdf"
        elif drive is not None and _real_speed(drive):
            limit, source = drive, "motor"
        else:
            limit, source = DEFAULT_LIMIT.get(kinds.get(joint, "hinge"), 100.0), "default"
        multiple = DRIVEN_MULTIPLE if joint in named else FREE_MULTIPLE
        unit = "m/s" if kinds.get(joint) == "slide" else "rad/s"
        result.append(
            JointSpeed(joint, speed, float(limit), source, multiple, unit, joint in unlimited)
        )
    return result


def _advice(speed: JointSpeed) -> str:
    """What to give a joint that went past its bound."""
    if speed.multiple == DRIVEN_MULTIPLE:
        return "something outside its drive throws it: check its neighbours' gains and force ranges"
    if speed.unlimited:
        return (
            "its servo has no force limit (the URDF gives no effort), so no torque-speed line "
            "holds it to its velocity: give it its real effort (a rule's forcerange) or its "
            "drive (a rule's motor: in actuators:)"
        )
    return (
        "give it its real drive (a rule's motor: in actuators:) or its real effort "
        "(a rule's forcerange), or lower actuators.frequency"
    )


def speed_results(speeds: list[JointSpeed], start: str = "") -> tuple[Speeds, list[str]]:
    """check.json's ``max_joint_speed`` (the fastest joint, with its limit) and
    ``speed_bound`` entries, and the failures; ``start`` says where the test that measured
    ``speeds`` began when not at qpos0."""
    from mjcfbuild.check.results import FastestJoint, Speeds

    failures = [
        f"joint '{s.joint}' reached {s.speed:.3g} {s.unit} under pseudorandom control"
        + (" from inside the joint ranges" if start else "")
        + f", more "
        f"than {s.multiple:g} times its velocity limit {s.limit:g} {s.unit} ({s.limit_from}); "
        + _advice(s)
        for s in speeds
        if s.fails
    ]
    worst = max(speeds, key=lambda s: (s.speed, s.joint), default=None)
    bound = Speeds(
        fastest=FastestJoint(worst.joint, worst.speed, worst.limit) if worst is not None else None,
        driven_multiple=DRIVEN_MULTIPLE,
        free_multiple=FREE_MULTIPLE,
        over_limit=[s for s in speeds if s.exceeds_limit],
        measured_from=start,
    )
    return bound, failures
