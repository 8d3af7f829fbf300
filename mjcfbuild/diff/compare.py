"""Two snapshots of a model turned into the changes a reviewer reads, in groups.

Numbers are compared as MuJoCo compiled them: the same sources compile to the same bits, so
the tolerances only absorb the last-digit noise of a recompiled mesh's centre.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

from mjcfbuild.actuators import READING_FIELDS
from mjcfbuild.diff.snapshot import Snapshot

GROUPS: tuple[tuple[str, str], ...] = (
    ("structure", "Bodies and joints"),
    ("kinematics", "Kinematics"),
    ("masses", "Masses and inertias"),
    ("joints", "Joint ranges and limits"),
    ("actuators", "Actuators and gains"),
    ("geometry", "Collision geometry"),
    ("matrix", "Collision matrix"),
    ("home", "Home pose"),
    ("checks", "Checks"),
    ("previews", "Previews"),
)

LENGTH_TOLERANCE = 1e-10  # m: kinematics are kept to 1e-12, so a larger move is an edit
RELATIVE_TOLERANCE = 1e-9


@dataclass(frozen=True)
class Change:
    """One change: what (``subject``, ``what``), its value before and after, and a note
    (how far a link moved, say)."""

    subject: str
    what: str
    before: Any
    after: Any
    note: str = ""


@dataclass
class ModelDiff:
    """The changes between two builds of a model, by group (see :data:`GROUPS`)."""

    groups: dict[str, list[Change]] = field(default_factory=dict)

    def add(self, group: str, change: Change) -> None:
        """Record one change in ``group``."""
        self.groups.setdefault(group, []).append(change)

    @property
    def empty(self) -> bool:
        """Whether nothing in the model changed."""
        return not any(self.groups.values())

    def to_dict(self) -> dict[str, Any]:
        """A JSON-friendly form, groups in :data:`GROUPS` order."""
        return {
            key: [asdict(change) for change in self.groups[key]]
            for key, _ in GROUPS
            if self.groups.get(key)
        }


def compare(before: Snapshot, after: Snapshot) -> ModelDiff:
    """What changed from ``before`` to ``after``."""
    diff = ModelDiff()
    _structure(diff, before, after)
    _kinematics(diff, before, after)
    _masses(diff, before, after)
    _joints(diff, before, after)
    _actuators(diff, before, after)
    _geometry(diff, before, after)
    _matrix(diff, before, after)
    _home(diff, before, after)
    _checks(diff, before.get("checks"), after.get("checks"))
    _previews(diff, before.get("previews", {}), after.get("previews", {}))
    return diff


def same(a: Any, b: Any, absolute: float = 0.0) -> bool:
    """Whether two values (numbers, lists of them, or anything else) are equal within
    :data:`RELATIVE_TOLERANCE` (and ``absolute``)."""
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if isinstance(a, bool) or isinstance(b, bool):
            return a == b
        return math.isclose(a, b, rel_tol=RELATIVE_TOLERANCE, abs_tol=absolute)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y, absolute) for x, y in zip(a, b, strict=True))
    return a == b


def _added_removed(diff, group, kind, before: dict, after: dict, describe) -> list[str]:
    """Record names only in one side; the names in both, sorted."""
    for name in sorted(set(after) - set(before)):
        diff.add(group, Change(f"{kind} {name}", "added", None, describe(after[name])))
    for name in sorted(set(before) - set(after)):
        diff.add(group, Change(f"{kind} {name}", "removed", describe(before[name]), None))
    return sorted(set(before) & set(after))


def _fields(diff, group: str, subject: str, old: dict, new: dict, names, absolute=0.0) -> None:
    for name in names:
        if not same(old.get(name), new.get(name), absolute):
            diff.add(group, Change(subject, name, old.get(name), new.get(name)))


def _structure(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    bodies = _added_removed(
        diff,
        "structure",
        "body",
        before["bodies"],
        after["bodies"],
        lambda body: f"child of {body['parent']}",
    )
    for name in bodies:
        old, new = before["bodies"][name]["parent"], after["bodies"][name]["parent"]
        if old != new:
            diff.add("structure", Change(f"body {name}", "parent", old, new))
    joints = _added_removed(
        diff,
        "structure",
        "joint",
        before["joints"],
        after["joints"],
        lambda joint: f"{joint['type']} on {joint['body']}",
    )
    for name in joints:
        _fields(diff, "structure", f"joint {name}", before["joints"][name],
                after["joints"][name], ("type", "body"))  # fmt: skip
    # A body's own site (named after it) comes and goes with the body: not said twice.
    frames_before = {k: v for k, v in before["frames"].items() if k not in before["bodies"]}
    frames_after = {k: v for k, v in after["frames"].items() if k not in after["bodies"]}
    _added_removed(
        diff, "structure", "frame", frames_before, frames_after,
        lambda frame: f"on {frame['body']}",
    )  # fmt: skip


def _distance(a: list[float], b: list[float]) -> float:
    return math.dist(a, b)


def _angle(a: list[float], b: list[float]) -> float:
    """The angle between two unit quaternions, radians; from the relative rotation's vector
    part (``acos`` of their dot product loses half the digits near zero)."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    w = aw * bw + ax * bx + ay * by + az * bz
    x = aw * bx - bw * ax - (ay * bz - az * by)
    y = aw * by - bw * ay - (az * bx - ax * bz)
    z = aw * bz - bw * az - (ax * by - ay * bx)
    return 2.0 * math.atan2(math.sqrt(x * x + y * y + z * z), abs(w))


def _moved(diff, subject: str, relative_to: str, old: dict, new: dict) -> None:
    distance = _distance(old["pos"], new["pos"])
    angle = _angle(old["quat"], new["quat"])
    if distance <= LENGTH_TOLERANCE and angle <= LENGTH_TOLERANCE:
        return
    parts = []
    if distance > LENGTH_TOLERANCE:
        parts.append(f"moved {distance:.6g} m")
    if angle > LENGTH_TOLERANCE:
        parts.append(f"turned {math.degrees(angle):.6g} deg")
    world = _distance(old["world_pos"], new["world_pos"])
    note = " and ".join(parts) + f" relative to {relative_to}"
    if abs(world - distance) > LENGTH_TOLERANCE:
        note += f" ({world:.6g} m in the world at the zero pose)"
    diff.add("kinematics", Change(subject, "pose", _pose(old), _pose(new), note))


def _pose(entry: dict) -> dict[str, list[float]]:
    return {"pos": entry["pos"], "quat": entry["quat"]}


def _kinematics(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    for name in sorted(set(before["bodies"]) & set(after["bodies"])):
        old, new = before["bodies"][name], after["bodies"][name]
        if old["parent"] == new["parent"]:
            _moved(diff, f"body {name}", old["parent"], old, new)
    for name in sorted(set(before["frames"]) & set(after["frames"])):
        old, new = before["frames"][name], after["frames"][name]
        if old["body"] == new["body"]:
            _moved(diff, f"frame {name}", old["body"], old, new)
    for name in sorted(set(before["joints"]) & set(after["joints"])):
        old, new = before["joints"][name]["axis"], after["joints"][name]["axis"]
        if not same(old, new, LENGTH_TOLERANCE):
            diff.add("kinematics", Change(f"joint {name}", "axis", old, new))


def _masses(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    total_before = sum(body["mass"] for body in before["bodies"].values())
    total_after = sum(body["mass"] for body in after["bodies"].values())
    if not same(total_before, total_after):
        diff.add("masses", Change("robot", "total mass", total_before, total_after))
    for name in sorted(set(before["bodies"]) & set(after["bodies"])):
        old, new = before["bodies"][name], after["bodies"][name]
        _fields(diff, "masses", f"body {name}", old, new, ("mass", "inertia"))
        _fields(diff, "masses", f"body {name}", old, new, ("com",), LENGTH_TOLERANCE)


def _joints(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    names = ("range", "force_range", "damping", "armature", "frictionloss")
    for name in sorted(set(before["joints"]) & set(after["joints"])):
        old, new = before["joints"][name], after["joints"][name]
        _fields(diff, "joints", f"joint {name}", old, new, names)


def _actuators(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    common = _added_removed(
        diff,
        "actuators",
        "actuator",
        before["actuators"],
        after["actuators"],
        lambda actuator: f"{actuator['kind']} on {actuator['target']}",
    )
    names = ("kind", "target", *(name for name in READING_FIELDS if name != "kind"))
    for name in common:
        old, new = before["actuators"][name], after["actuators"][name]
        _fields(diff, "actuators", f"actuator {name}", old, new, names)


def _describe_geom(geom: dict) -> str:
    if geom["type"] == "mesh":
        return f"mesh {geom['mesh']} ({geom['vertices']} vertices)"
    return f"{geom['type']} size {' '.join(f'{v:.6g}' for v in geom['size'])}"


def _geometry(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    for body in sorted(set(before["bodies"]) & set(after["bodies"])):
        for kind in ("collision", "visual"):
            old = before["geometry"].get(body, {}).get(kind, [])
            new = after["geometry"].get(body, {}).get(kind, [])
            _geom_lists(diff, f"body {body}", kind, old, new)


def _geom_lists(diff: ModelDiff, subject: str, kind: str, old: list, new: list) -> None:
    if len(old) != len(new):
        diff.add(
            "geometry",
            Change(
                subject,
                f"{kind} geoms",
                [_describe_geom(g) for g in old],
                [_describe_geom(g) for g in new],
                f"{len(old)} -> {len(new)}",
            ),
        )
        return
    for index, (a, b) in enumerate(zip(old, new, strict=True)):
        label = f"{kind} geom {index + 1}"
        if a["type"] != b["type"] or a.get("mesh") != b.get("mesh"):
            diff.add("geometry", Change(subject, label, _describe_geom(a), _describe_geom(b)))
        elif a["type"] == "mesh" and a["digest"] != b["digest"]:
            diff.add(
                "geometry",
                Change(subject, f"{label}: mesh {a['mesh']}", _mesh_size(a), _mesh_size(b),
                       "its vertices or faces changed"),
            )  # fmt: skip
        elif a["type"] != "mesh" and not same(a["size"], b["size"]):
            diff.add("geometry", Change(subject, f"{label} size", a["size"], b["size"]))
        elif not same(a["pos"], b["pos"], 1e-7):
            diff.add("geometry", Change(subject, f"{label} position", a["pos"], b["pos"]))


def _mesh_size(geom: dict) -> dict[str, Any]:
    return {"vertices": geom["vertices"], "faces": geom["faces"], "extent": geom["extent"]}


def _matrix(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    old = {tuple(pair) for pair in before["excludes"]}
    new = {tuple(pair) for pair in after["excludes"]}
    for pair in sorted(new - old):
        diff.add("matrix", Change(f"{pair[0]} / {pair[1]}", "contact", "collide", "excluded"))
    for pair in sorted(old - new):
        diff.add("matrix", Change(f"{pair[0]} / {pair[1]}", "contact", "excluded", "collide"))
    reasons_before = before.get("collision_reasons", {})
    reasons_after = after.get("collision_reasons", {})
    for key in sorted(set(reasons_before) | set(reasons_after)):
        old_reason, new_reason = reasons_before.get(key), reasons_after.get(key)
        if old_reason != new_reason:
            first, second = key.split("|", 1)
            diff.add("matrix", Change(f"{first} / {second}", "reason", old_reason, new_reason))


def _home(diff: ModelDiff, before: Snapshot, after: Snapshot) -> None:
    old, new = before.get("home"), after.get("home")
    if old is None or new is None:
        if (old is None) != (new is None):
            diff.add("home", Change("keyframe home", "present", old is not None, new is not None))
        return
    sources_before = before.get("home_sources", {})
    sources_after = after.get("home_sources", {})
    for part, kind in (("qpos", "joint"), ("ctrl", "actuator")):
        for name in sorted(set(old[part]) & set(new[part])):
            if not same(old[part][name], new[part][name], 1e-12):
                note = ""
                if part == "qpos" and name in sources_after:
                    source = sources_before.get(name, "?")
                    changed = source != sources_after[name]
                    note = f"set by {source + ' -> ' if changed else ''}{sources_after[name]}"
                change = Change(f"{kind} {name}", part, old[part][name], new[part][name], note)
                diff.add("home", change)


def _checks(diff: ModelDiff, old: dict | None, new: dict | None) -> None:
    if old is None or new is None:
        if (old is None) != (new is None):
            diff.add("checks", Change("check", "ran", old is not None, new is not None))
        return
    if old["passes"] != new["passes"]:
        verdict = {True: "passed", False: "failed"}
        result = Change("check", "result", verdict[old["passes"]], verdict[new["passes"]])
        diff.add("checks", result)
    for failure in new["failures"]:
        if failure not in old["failures"]:
            diff.add("checks", Change("check", "new failure", None, failure))
    for failure in old["failures"]:
        if failure not in new["failures"]:
            diff.add("checks", Change("check", "fixed failure", failure, None))
    stand_old, stand_new = old.get("stand") or {}, new.get("stand") or {}
    if stand_old.get("verdict") != stand_new.get("verdict"):
        note = ""
        if stand_new.get("max_tilt") is not None:
            note = f"base tilted {stand_new['max_tilt']:.3g} rad at most"
        diff.add(
            "checks",
            Change("stand test", "robot", stand_old.get("verdict"), stand_new.get("verdict"), note),
        )
    for name in ("hold_deviation", "menagerie_finite", "menagerie_warnings"):
        if not same(old.get(name), new.get(name), 1e-9):
            diff.add("checks", Change("check", name, old.get(name), new.get(name)))


def _previews(diff: ModelDiff, old: dict[str, str], new: dict[str, str]) -> None:
    for name in sorted(set(old) | set(new)):
        if old.get(name) != new.get(name):
            what = "added" if name not in old else "removed" if name not in new else "changed"
            diff.add("previews", Change(name, what, old.get(name), new.get(name)))
