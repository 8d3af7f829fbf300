"""The check's results, typed: what ``check.json`` holds, and the one way to read and write it.

The build's check task and ``mjcfbuild check`` produce a :class:`CheckResults`
(``steps.check.check_built``); the report, the page, the package's README, ``mjcfbuild diff``
and the console read it, never the file's keys. Each section is a frozen record whose fields
are its keys in check.json, so :meth:`CheckResults.to_json` writes the same bytes the check
always wrote (sorted keys, one-space indent), and :meth:`CheckResults.from_json` reads them
back, a file of an older mjcfbuild included: a key it lacks takes the field's default.

A new check adds its section here (a record, a field of :class:`CheckResults`, its console
line and report row), its own module under ``check/``, and the call that runs it in
``check/model_check.py`` (``steps/check.py`` for one that needs the build's records): the
readers need no change.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, fields, is_dataclass, replace
from pathlib import Path
from typing import Any, TypeVar

from mjcfbuild.check.contacts import RestingContact
from mjcfbuild.check.findings import BodyFinding
from mjcfbuild.check.parts import PartResult
from mjcfbuild.check.speeds import JointSpeed
from mjcfbuild.markup import markdown_text as md
from mjcfbuild.numbers import beside

R = TypeVar("R")

CANNOT_STAND = "the robot cannot stand without a controller"


def plural(count: int, noun: str, nouns: str | None = None) -> str:
    """``count`` and ``noun``, with an s where it is not one (or ``nouns``, where given)."""
    return f"{count} {noun if count == 1 else (nouns or noun + 's')}"


def to_plain(value: Any) -> Any:
    """``value`` as check.json holds it: records as dicts, lists and dicts of them likewise."""
    if is_dataclass(value) and not isinstance(value, type):
        to_dict = getattr(value, "to_dict", None)
        return (
            to_dict()
            if to_dict
            else {f.name: to_plain(getattr(value, f.name)) for f in fields(value)}
        )
    if isinstance(value, list | tuple):
        return [to_plain(item) for item in value]
    if isinstance(value, dict):
        return {key: to_plain(item) for key, item in value.items()}
    return value


def _record(cls: type[R], data: Any, **nested: Callable[[Any], Any]) -> R:
    """A record of ``cls`` from its dict in check.json: keys it does not have are dropped, keys
    the dict lacks take the field's default, ``nested`` turns a key's value into its type."""
    if not isinstance(data, dict):
        data = {}
    names = {f.name for f in fields(cls)}  # type: ignore[arg-type]
    values = {key: value for key, value in data.items() if key in names}
    for key, read in nested.items():
        if values.get(key) is not None:
            values[key] = read(values[key])
    return cls(**values)


def _listed(cls: type[R]) -> Callable[[Any], list[R]]:
    """A reader of a list of ``cls`` records."""
    return lambda items: [_record(cls, item) for item in items if isinstance(item, dict)]


@dataclass(frozen=True)
class Simulation:
    """Zero-control steps of the scene (or the model alone)."""

    model: str = ""
    steps: int = 0
    finite: bool = True
    warnings: list[str] = field(default_factory=list)
    stopped: str | None = None  # the MuJoCo error that stopped it

    def to_dict(self) -> dict[str, Any]:
        """As check.json holds it (``stopped`` only when it stopped)."""
        data = {f.name: to_plain(getattr(self, f.name)) for f in fields(self)}
        if self.stopped is None:
            del data["stopped"]
        return data


# How the console marks a check that failed, before its figures.
FAILED = "FAILED: "


@dataclass(frozen=True)
class Kinematics:
    """Every URDF link's pose in the model against the reference's, at random configurations."""

    configurations: int = 0
    max_position_error: float = 0.0
    max_rotation_error: float = 0.0
    worst_link: str | None = None
    missing_links: list[str] = field(default_factory=list)
    missing_joints: list[str] = field(default_factory=list)
    reference: str = ""  # who read the URDF: yourdfpy, or mjcfbuild's parser and why
    failed: bool = False  # a link is missing or past the tolerances


@dataclass(frozen=True)
class Joints:
    """Joint types, axes and ranges against the URDF."""

    problems: list[str] = field(default_factory=list)
    relative_tolerance: float = 0.0


@dataclass(frozen=True)
class Masses:
    """Masses, centres of mass and inertias against the URDF."""

    urdf_total: float = 0.0
    model_total: float = 0.0
    problems: list[str] = field(default_factory=list)
    repaired_bodies: list[str] = field(default_factory=list)
    # Moving bodies with geometry whose every link lacks a mass in the URDF (no <inertial>, or
    # mass 0): the model moves them with the build's placeholder, not the robot's mass.
    placeholder_bodies: list[str] = field(default_factory=list)
    # Links without a mass in the URDF given the mass of their geometry (robot.yaml's
    # inertia.missing: geometry), their total and the density: in the model, not the URDF.
    from_geometry: list[str] = field(default_factory=list)
    geometry_total: float = 0.0
    geometry_density: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        """As check.json holds it (the masses from geometry only where there are some)."""
        data = {f.name: to_plain(getattr(self, f.name)) for f in fields(self)}
        if not self.from_geometry:
            for name in ("from_geometry", "geometry_total", "geometry_density"):
                del data[name]
        return data

    def geometry_note(self) -> str:
        """What of the model's mass the build gave links from their geometry, '' for none."""
        if not self.from_geometry:
            return ""
        count = len(self.from_geometry)
        return (
            f"{self.geometry_total:.6g} kg of it from the geometry of {plural(count, 'link')} "
            f"without a mass in the URDF, at {self.geometry_density:g} kg/m^3: "
            "inertia.missing: geometry"
        )


@dataclass(frozen=True)
class PartContact:
    """Two bodies of one MJCF part touching at home: the part's own behaviour, not a failure."""

    part: str = ""
    body1: str = ""
    body2: str = ""
    depth: float = 0.0
    pose: str = ""


@dataclass(frozen=True)
class RestingContacts:
    """Robot bodies touching at home, and the contact excludes that would let them be."""

    pairs: list[RestingContact] = field(default_factory=list)
    exclude: str = ""
    inside_parts: list[PartContact] = field(default_factory=list)

    @classmethod
    def from_dict(cls, data: Any) -> RestingContacts:
        """From check.json."""
        return _record(cls, data, pairs=_listed(RestingContact), inside_parts=_listed(PartContact))


@dataclass(frozen=True)
class Actuation:
    """Every moving joint driven by exactly one actuator."""

    actuators: int = 0
    problems: list[str] = field(default_factory=list)
    # Whether the problems fail the check: only for a model mjcfbuild built.
    required: bool = True


@dataclass(frozen=True)
class FloorGap:
    """A floating robot's lowest collision geometry at home above (+) or below the floor."""

    gap: float | None = None  # m; None where there is no collision geometry to measure


@dataclass(frozen=True)
class Hold:
    """Holding home's ctrl for 1 s."""

    max_deviation: float = 0.0
    joint: str | None = None
    floating: bool = False
    base_tilt: float | None = None
    failed: bool = False  # a fixed base moved past check.hold_tolerance
    held: int = 0  # hinge and slide joints the hold watched (not asked to be passive)
    passive: int = 0  # hinge and slide joints asked to have no actuator
    passive_deviation: float = 0.0  # the largest distance from home of one of them
    passive_joint: str | None = None
    passive_sags: bool = False  # of a fixed base, past check.hold_tolerance: it holds no pose

    def passive_words(self) -> str:
        """How the joints without an actuator moved, '' where there are none."""
        if not self.passive:
            return ""
        count = f"{self.passive} joint{'s' if self.passive > 1 else ''} without an actuator"
        if not self.passive_joint:
            return f"{count} did not move"
        return f"{count} moved up to {self.passive_deviation:.3g} ({self.passive_joint})"


@dataclass(frozen=True)
class Stand:
    """A floating robot holding home's ctrl for 5 s on the floor (control.stand_test.StandTest)."""

    seconds: float = 0.0
    max_tilt: float = 0.0
    max_sink: float = 0.0
    home_height: float = 0.0
    max_deviation: float = 0.0
    joint: str | None = None
    needs_controller: str = ""  # why it cannot stand at all; the test did not run
    com_margin: float = 0.0
    wheels: list[str] = field(default_factory=list)
    max_roll: float = 0.0
    wheel_kv: float = 0.0
    fell_without_controller: str = ""  # why it fell: torque motors cannot hold a pose
    failed: bool = False  # it fell, sank, rolled or bent past the tolerances

    def to_dict(self) -> dict[str, Any]:
        """As check.json holds it (``fell_without_controller`` only when it fell so)."""
        data = {f.name: to_plain(getattr(self, f.name)) for f in fields(self)}
        if not self.fell_without_controller:
            del data["fell_without_controller"]
        return data


@dataclass(frozen=True)
class MenagerieResult:
    """MuJoCo Menagerie's model test: 1 s of pseudorandom control."""

    warnings: list[str] = field(default_factory=list)
    finite: bool = True
    fastest_joint: str | None = None
    fastest_speed: float = 0.0
    unstable_joint: str | None = None


@dataclass(frozen=True)
class FastestJoint:
    """The joint fastest under pseudorandom control, with its velocity limit."""

    joint: str = ""
    speed: float = 0.0
    limit: float = 0.0


@dataclass(frozen=True)
class Speeds:
    """The speed bound (check.speeds): in check.json, ``max_joint_speed`` and ``speed_bound``."""

    fastest: FastestJoint | None = None
    driven_multiple: float = 0.0
    free_multiple: float = 0.0
    over_limit: list[JointSpeed] = field(default_factory=list)
    measured_from: str = ""  # where the test began, when not at qpos0

    def to_dict(self) -> dict[str, Any]:
        """The two keys of check.json."""
        bound = {
            "driven_multiple": self.driven_multiple,
            "free_multiple": self.free_multiple,
            "over_limit": to_plain(self.over_limit),
        }
        if self.measured_from:
            bound["measured_from"] = self.measured_from
        return {"max_joint_speed": to_plain(self.fastest), "speed_bound": bound}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Speeds | None:
        """From check.json (None where the bound was not measured)."""
        if "speed_bound" not in data and "max_joint_speed" not in data:
            return None
        bound = _record(cls, data.get("speed_bound"), over_limit=_listed(JointSpeed))
        fastest = data.get("max_joint_speed")
        return replace(bound, fastest=_record(FastestJoint, fastest) if fastest else None)


@dataclass(frozen=True)
class MeshStatistics:
    """One body's mesh vertices and faces, visual and collision, and its convex parts."""

    body: str = ""
    visual_vertices: int = 0
    visual_faces: int = 0
    collision_vertices: int = 0
    collision_faces: int = 0
    convex_parts: int = 0


@dataclass(frozen=True)
class PlausibilityResults:
    """The plausibility test (check.plausibility): the bodies it named and why."""

    bodies: int = 0
    findings: list[BodyFinding] = field(default_factory=list)
    failures: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @classmethod
    def from_dict(cls, data: Any) -> PlausibilityResults:
        """From check.json."""
        return _record(cls, data, findings=_listed(BodyFinding))


@dataclass(frozen=True)
class Runtime:
    """What mujoco_ros2_control makes of the <ros2_control> block (check.runtime); the rows
    are check.runtime's own records."""

    joints: list[dict[str, Any]] = field(default_factory=list)
    sensors: list[dict[str, Any]] = field(default_factory=list)
    devices: list[dict[str, Any]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    failed: bool = False  # the runtime would not drive or read something the block names


@dataclass(frozen=True)
class GazeboSensor:
    """A URDF Gazebo sensor: whether the model has it, and what of it MuJoCo does not model."""

    name: str = ""
    type: str = ""
    reference: str = ""
    modelled: bool = False
    not_modelled: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class CheckResults:
    """Every result of the check of a model, and the failures among them. A section is None
    where its check did not run (the model did not load, it has no home keyframe...)."""

    loads: bool = False
    failures: list[str] = field(default_factory=list)
    simulation: Simulation | None = None
    kinematics: Kinematics | None = None
    joints: Joints | None = None
    masses: Masses | None = None
    resting_contacts: RestingContacts | None = None
    actuation: Actuation | None = None
    home: bool | None = None  # whether the model has a home keyframe
    floor: FloorGap | None = None
    hold: Hold | None = None
    stand: Stand | None = None
    needs_controller: str = ""  # why the robot cannot stand without one ('' if it can)
    menagerie_test: MenagerieResult | None = None
    speeds: Speeds | None = None
    meshes: list[MeshStatistics] | None = None
    plausibility: PlausibilityResults | None = None
    parts: dict[str, PartResult] | None = None  # by the MJCF part's prefix
    mujoco_ros2_control: Runtime | None = None
    gazebo_sensors: list[GazeboSensor] | None = None

    @property
    def passes(self) -> bool:
        """Whether every check passed."""
        return not self.failures

    def add(self, failures: Sequence[str] = (), **sections: Any) -> CheckResults:
        """These results with ``sections`` set and ``failures`` added."""
        return replace(self, failures=[*self.failures, *failures], **sections)

    def to_dict(self) -> dict[str, Any]:
        """check.json's content: whether it passes, the console's verdict, the failures and
        every section that ran."""
        # The console's verdict, for the build's summary to print without reading the rest.
        data: dict[str, Any] = {"passes": self.passes, "verdict": self.console_verdict()}
        for item in fields(self):
            value = getattr(self, item.name)
            if value is None or (item.name == "needs_controller" and not value):
                continue
            if item.name == "speeds":
                data.update(value.to_dict())
            elif item.name == "floor":
                data["floor_gap"] = value.gap
            else:
                data[item.name] = to_plain(value)
        return data

    def to_json(self) -> bytes:
        """check.json's bytes."""
        return (json.dumps(self.to_dict(), indent=1, sort_keys=True) + "\n").encode()

    @classmethod
    def from_dict(cls, data: Any) -> CheckResults:
        """The results check.json holds (an empty record where it holds none)."""
        if not isinstance(data, dict):
            data = {}
        parts = data.get("parts")
        results = _record(
            cls,
            data,
            simulation=lambda d: _record(Simulation, d),
            kinematics=lambda d: _record(Kinematics, d),
            joints=lambda d: _record(Joints, d),
            masses=lambda d: _record(Masses, d),
            resting_contacts=RestingContacts.from_dict,
            actuation=lambda d: _record(Actuation, d),
            hold=lambda d: _record(Hold, d),
            stand=lambda d: _record(Stand, d),
            menagerie_test=lambda d: _record(MenagerieResult, d),
            meshes=_listed(MeshStatistics),
            plausibility=PlausibilityResults.from_dict,
            mujoco_ros2_control=lambda d: _record(Runtime, d),
            gazebo_sensors=_listed(GazeboSensor),
        )
        return replace(
            results,
            floor=FloorGap(data["floor_gap"]) if "floor_gap" in data else None,
            speeds=Speeds.from_dict(data),
            parts={
                prefix: _record(PartResult, part)
                for prefix, part in parts.items()
                if isinstance(part, dict)
            }
            if isinstance(parts, dict)
            else None,
        )

    @classmethod
    def from_json(cls, text: str | bytes) -> CheckResults:
        """The results of check.json's text (ValueError where it is not JSON)."""
        return cls.from_dict(json.loads(text))

    @classmethod
    def read(cls, path: Path) -> CheckResults | None:
        """The results in check.json at ``path``; None where there are none to read (the build
        did not check, or the file is not a check's)."""
        try:
            data = json.loads(path.read_bytes())
            return cls.from_dict(data) if isinstance(data, dict) else None
        except (OSError, ValueError, TypeError):  # TypeError: a record without its keys
            return None

    def stand_verdict(self) -> str | None:
        """A floating robot's stand test in a word: "stands", "falls" or "needs a controller";
        None for a robot that was not stood (fixed, or no home)."""
        if self.stand is None:
            return None
        if any("does not stand" in failure for failure in self.failures):
            return "falls"
        # Torque motors that let it fall: a controller's job, not a failure (check.control).
        needs = self.stand.needs_controller or self.stand.fell_without_controller
        return "needs a controller" if needs else "stands"

    def standing_note(self, escape: Callable[[str], str] = str, warning: bool = False) -> str:
        """Why the robot cannot stand without a controller, '' where it can: the words of the
        report's verdict and the console (``escape`` for Markdown), or with ``warning`` the
        build's warning, which also says what the model then holds."""
        why = self.needs_controller
        if not why:
            return ""
        ran = bool(self.stand and self.stand.fell_without_controller)
        if warning:
            return f"{CANNOT_STAND}: {why}" + (
                ""
                if ran
                else "; the stand test was not run, and the model holds its joints, not its balance"
            )
        return f"{CANNOT_STAND} ({escape(why)})" + ("" if ran else ": the stand test was not run")

    def warnings(self) -> list[str]:
        """What the check found worth a warning that is not a failure."""
        standing = self.standing_note(warning=True)
        return (
            ([standing] if standing else [])
            + (self.plausibility.warnings if self.plausibility else [])
            + (self.mujoco_ros2_control.warnings if self.mujoco_ros2_control else [])
        )

    def console_lines(self) -> list[tuple[str, str]]:
        """Each check that ran (or was skipped) and its result, as the console shows them; a
        check that failed says so first (``FAILED:``), before its figures."""
        if not self.loads:
            return [("loads", "FAILED: the model does not load")]
        lines = [("loads", "yes")]

        def add(name: str, result: str, failed: bool = False) -> None:
            lines.append((name, f"{FAILED}{result}" if failed else result))

        if self.simulation:
            sim = self.simulation
            result = (
                "STOPPED by a MuJoCo error"
                if sim.stopped
                else f"{'finite' if sim.finite else 'NOT FINITE'}, "
                f"{plural(len(sim.warnings), 'MuJoCo warning')}"
            )
            failed = bool(sim.stopped or not sim.finite or sim.warnings)
            add(f"{sim.steps} zero-control steps", result, failed)
        if self.kinematics:
            kin = self.kinematics
            missing = f", {len(kin.missing_links)} links missing" if kin.missing_links else ""
            add(
                "link poses",
                f"max {kin.max_position_error:.2g} m, {kin.max_rotation_error:.2g} rad at "
                f"{kin.configurations} configurations{missing}",
                kin.failed,
            )
        if self.joints:
            add("joints", plural(len(self.joints.problems), "problem"), bool(self.joints.problems))
        if self.masses:
            masses = self.masses
            placeholders = (
                f", {plural(len(masses.placeholder_bodies), 'moving body', 'moving bodies')} "
                "without a mass in the URDF"
                if masses.placeholder_bodies
                else ""
            )
            note = masses.geometry_note()
            add(
                "masses",
                f"{masses.model_total:.6g} kg (URDF {masses.urdf_total:.6g} kg"
                f"{'; ' + note if note else ''}), "
                f"{plural(len(masses.problems), 'problem')}{placeholders}",
                bool(masses.problems),
            )
        if self.resting_contacts:
            pairs = self.resting_contacts.pairs
            add("resting contacts", str(len(pairs)) if pairs else "none")
        if self.actuation is not None:
            actuation = self.actuation
            problems = len(actuation.problems)
            result = f"{plural(actuation.actuators, 'actuator')}, {plural(problems, 'problem')}"
            if problems and not actuation.required:
                result += " (not required of a model mjcfbuild did not build)"
            add("every moving joint driven", result, bool(problems) and actuation.required)
        if self.floor is not None and self.floor.gap is not None:
            add("on the floor at home", f"gap {self.floor.gap * 1000:.2g} mm")
        if self.hold:
            hold = self.hold
            joint = f" ({hold.joint})" if hold.joint else ""
            deviation = (
                "every joint is passive"
                if hold.passive and not hold.held
                else f"largest deviation {hold.max_deviation:.3g}{joint}"
            )
            passive = hold.passive_words()
            if hold.floating and self.stand and self.stand.needs_controller:
                deviation += ", not judged: the stand test below was not run"
            elif hold.floating:  # it stands on the floor, or falls, as it holds: one judge
                deviation += ", judged by the stand test below"
            add("hold home 1 s", f"{deviation}; {passive}" if passive else deviation, hold.failed)
        stand = self.stand
        if stand and stand.fell_without_controller:
            add("stand 5 s", f"FELL: needs a controller ({stand.fell_without_controller})")
        elif stand and stand.needs_controller:
            add("stand 5 s", f"NOT RUN: needs a controller ({stand.needs_controller})")
        elif stand:
            add(
                f"stand {stand.seconds:g} s",
                f"tilt {stand.max_tilt:.2g} rad, sank {stand.max_sink * 1000:.0f} mm",
                stand.failed,
            )
        elif self.home is False:
            add("hold and stand", "NOT RUN: the model has no home keyframe")
        if self.menagerie_test:
            test = self.menagerie_test
            add(
                "1 s pseudorandom control",
                f"{'finite' if test.finite else 'NOT FINITE'}, "
                f"{plural(len(test.warnings), 'MuJoCo warning')}",
                bool(not test.finite or test.warnings),
            )
        fastest = self.speeds.fastest if self.speeds else None
        if fastest:
            add("joint speeds", *self._speed_line(fastest))
        if self.plausibility:
            found = self.plausibility
            add(
                "plausibility",
                f"{plural(len(found.failures), 'failure')}, "
                f"{plural(len(found.warnings), 'warning')}",
                bool(found.failures),
            )
        for prefix, part in sorted((self.parts or {}).items()):
            where = f"MJCF part {prefix}"
            add(
                where,
                f"max {part.max_position_error:.2g} m, {plural(len(part.problems), 'problem')}",
                any(failure.startswith(f"{where} (") for failure in self.failures),
            )
        if self.mujoco_ros2_control:
            runtime = self.mujoco_ros2_control
            add(
                "mujoco_ros2_control",
                f"{plural(len(runtime.joints), 'joint')}, "
                f"{plural(len(runtime.sensors), 'sensor')}, "
                f"{len(runtime.devices)} cameras and lidars",
                runtime.failed,
            )
        return lines

    def _speed_line(self, fastest: FastestJoint) -> tuple[str, bool]:
        """The console's joint speeds, and whether a joint went past its bound: faster than
        its velocity limit is listed (the real joint could not), failed only past the bound
        (check.speeds: that many times the limit)."""
        over = self.speeds.over_limit if self.speeds else []
        failing = [speed for speed in over if speed.fails]
        line = (
            f"fastest {fastest.joint} {beside(fastest.speed, fastest.limit)} "
            f"(limit {fastest.limit:g})"
        )
        if not over:
            return f"{line}, within the bound", False
        worst = max(failing or over, key=lambda speed: (speed.speed / speed.limit, speed.joint))
        most = f"{worst.joint} at {beside(worst.speed / worst.limit, 1.0)} times its limit"
        if failing:
            return f"{line}; {len(failing)} past the bound ({most})", True
        joints = (
            "1 joint faster than its limit"
            if len(over) == 1
            else (f"{len(over)} joints faster than their limits")
        )
        return f"{line}; {joints}, within the bound ({most})", False

    def console_verdict(self, place: Callable[[str], str] = str) -> str:
        """The verdict the console gives: how many checks failed, or that they pass and what
        they did not prove, or "check passed"; ``place`` names the warning it quotes where
        the build's warnings are named (a xacro source's line)."""
        if not self.passes:
            return f"{len(self.failures)} check(s) failed"
        caveats = self.caveats()
        if caveats:
            return f"checks pass, but {'; '.join(caveats)}"
        warnings = self.warnings()  # the caveats hold the standing note: these are others
        if warnings:
            count = f"{len(warnings)} warning{'s' if len(warnings) > 1 else ''}"
            return f"checks pass with {count}: {place(warnings[0])}"
        return "check passed"

    def caveats(self, escape: Callable[[str], str] = str) -> list[str]:
        """What a passing check did not prove, for its verdict (``escape`` for Markdown):
        checks that did not run, and problems reported but not failed (of a model mjcfbuild
        did not build)."""
        found = []
        actuation = self.actuation
        if actuation is not None and actuation.problems and not actuation.required:
            shown = "; ".join(escape(problem) for problem in actuation.problems[:2])
            more = f"; {len(actuation.problems) - 2} more" if len(actuation.problems) > 2 else ""
            count = len(actuation.problems)
            found.append(
                f"{count} actuation problem{'s' if count > 1 else ''} ({shown}{more}): a "
                "controller cannot drive every joint"
            )
        if self.home is False:
            found.append("the hold and stand tests were not run: the model has no home keyframe")
        hold = self.hold
        if hold is not None and hold.passive_sags:
            found.append(
                f"it does not hold home: {plural(hold.passive, 'joint')} without an actuator "
                f"(as robot.yaml's actuators ask) {'move' if hold.passive > 1 else 'moves'} "
                "from it, "
                f"'{escape(hold.passive_joint or '')}' by {hold.passive_deviation:.3g} in 1 s"
            )
        standing = self.standing_note(escape)
        if standing:
            found.append(standing)
        placeholders = self.masses.placeholder_bodies if self.masses is not None else []
        if placeholders:
            count = len(placeholders)
            shown = ", ".join(f"'{escape(body)}'" for body in placeholders[:3])
            if count > 3:
                shown += f", {count - 3} more"
            found.append(
                f"{plural(count, 'moving body', 'moving bodies')} ({shown}) "
                f"{'have' if count > 1 else 'has'} no mass in the URDF (no <inertial>): the "
                f"model moves {'them' if count > 1 else 'it'} with a placeholder mass, so its "
                "dynamics are not the robot's"
            )
        return found

    def table_rows(self) -> list[str]:
        """The rows of report.md's table of checks (Markdown, names escaped)."""
        rows = [f"| loads | {'yes' if self.loads else 'no'} |"]
        if self.simulation:
            sim = self.simulation
            rows.append(
                f"| {sim.steps} zero-control steps of {md(sim.model)} | "
                f"{'finite' if sim.finite else 'NOT finite'}, "
                f"{len(sim.warnings)} MuJoCo warnings |"
            )
        if self.kinematics:
            kin = self.kinematics
            rows.append(
                f"| link poses at {kin.configurations} configurations | max error "
                f"{kin.max_position_error:.2g} m, {kin.max_rotation_error:.2g} rad; "
                f"{len(kin.missing_links)} links missing |"
            )
        for prefix, part in sorted((self.parts or {}).items()):
            rows.append(
                f"| MJCF part {md(prefix)} ({md(part.label)}) against the part alone, at "
                f"{part.configurations} configurations | max error "
                f"{part.max_position_error:.2g} m, {part.max_rotation_error:.2g} rad; "
                f"{len(part.missing)} missing, {len(part.problems)} problems |"
            )
        if self.actuation is not None:
            rows.append(
                f"| every moving joint driven once | {self.actuation.actuators} actuators, "
                f"{len(self.actuation.problems)} problems |"
            )
        if self.floor is not None and self.floor.gap is not None:
            rows.append(f"| floating base on the floor at home | gap {self.floor.gap:.2g} m |")
        if self.hold:
            hold = self.hold
            where = f" ({md(hold.joint)})" if hold.joint else ""
            tilted = (
                f"; the base tilted {hold.base_tilt:.2g} rad" if hold.base_tilt is not None else ""
            )
            passive = f"; {md(hold.passive_words())}" if hold.passive else ""
            rows.append(
                f"| hold home's ctrl for 1 s | largest deviation {hold.max_deviation:.3g}{where}"
                f"{tilted}{passive} |"
            )
        stand = self.stand
        if stand and stand.fell_without_controller:
            rows.append(f"| stand at home for 5 s | fell: {md(stand.fell_without_controller)} |")
        elif stand and stand.needs_controller:
            rows.append(f"| stand at home for 5 s | not run: {md(stand.needs_controller)} |")
        elif stand:
            joint = f" ({md(stand.joint)})" if stand.joint else ""  # none moved, or none held
            rows.append(
                f"| stand at home holding its ctrl for {stand.seconds:g} s | base tilted "
                f"{stand.max_tilt:.2g} rad, sank {stand.max_sink * 1000:.0f} mm; largest "
                f"joint deviation {stand.max_deviation:.3g}{joint} |"
            )
        if self.menagerie_test:
            test = self.menagerie_test
            rows.append(
                "| 1 s of pseudorandom control (Menagerie's model test) | "
                f"{'finite' if test.finite else 'NOT finite'}, "
                f"{len(test.warnings)} MuJoCo warnings |"
            )
        joint_problems = len(self.joints.problems) if self.joints else 0
        rows.append(f"| joint types, axes, ranges | {joint_problems} problems |")
        if self.masses:
            masses = self.masses
            note = masses.geometry_note()
            rows.append(
                f"| masses and inertias | total {masses.urdf_total:.6g} kg in the URDF, "
                f"{masses.model_total:.6g} kg in the model"
                f"{' (' + md(note) + ')' if note else ''}; {len(masses.problems)} problems |"
            )
        # The console's other checks, in its words: the report leaves out none it shows.
        console = dict(self.console_lines())
        for label in ("resting contacts", "joint speeds", "plausibility", "mujoco_ros2_control"):
            if label in console:
                rows.append(f"| {label} | {md(console[label])} |")
        return rows
