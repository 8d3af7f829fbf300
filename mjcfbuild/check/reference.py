"""The check's reference kinematics, read from the URDF by an independent reader (yourdfpy).

The build parses the URDF with mjcfbuild's own parser. If the check computed its reference
poses from that same parse, a parser bug (an origin read wrongly, a joint axis dropped) would
pass both. The reference therefore comes from yourdfpy, which reads the URDF text on its own,
mimic joints included; mjcfbuild's parse only supplies names and lines for messages.

yourdfpy reads the URDF in a task of its own (``reference``), which keeps what it read - each
joint's type, links, origin matrix, axis and mimic - as a *record*; the check computes link
poses from the record the way yourdfpy does. Importing yourdfpy (and trimesh and scipy with
it) takes about a second of CPU, which a build now spends only when the URDF's kinematics
change: the task reruns when :func:`kinematic_digest` of the URDF text changes, so a damping
or inertia edit does not rerun it.
"""

from __future__ import annotations

import hashlib
import io
import json
import math
from collections import defaultdict
from typing import Any

from mjcfbuild.urdf.transforms import Transform

Matrix = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]
READER = "yourdfpy"
MOVING = ("revolute", "continuous", "prismatic")
# What yourdfpy takes from a <joint> for forward kinematics.
_JOINT_PARTS = ("parent", "child", "origin", "axis", "mimic")


def kinematic_digest(urdf: bytes) -> str:
    """A digest of what the reference reads from the URDF text: the links' names and each
    joint's name, type, parent, child, origin, axis and mimic, as written. Any other change
    (dynamics, limits, inertia, geometry, comments) leaves it alone."""
    from lxml import etree

    try:
        parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True)
        root = etree.fromstring(urdf, parser)
    except etree.XMLSyntaxError:
        return "text:" + hashlib.sha256(urdf).hexdigest()  # unreadable: any change counts
    links = [element.get("name") for element in root.findall("link")]
    joints = [
        [sorted(joint.attrib.items()), [[p, sorted(e.attrib.items())] for p, e in _parts(joint)]]
        for joint in root.findall("joint")
    ]
    text = json.dumps([links, joints], separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def reader_input_digest(urdf: bytes) -> str:
    """A digest of the URDF text as the reader sees it: without its comments (xacro writes the
    source's absolute path into one), so that the same description in another folder has the
    same digest; of the bytes when the text is not XML."""
    from lxml import etree

    try:
        parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True)
        # The whole document, so that an entity the DOCTYPE defines counts.
        text = etree.tostring(etree.fromstring(urdf, parser).getroottree())
    except etree.XMLSyntaxError:
        return "text:" + hashlib.sha256(urdf).hexdigest()
    return hashlib.sha256(text).hexdigest()


def _parts(joint: Any) -> list[tuple[str, Any]]:
    return [(part, element) for part in _JOINT_PARTS for element in joint.findall(part)]


def read_kinematics(urdf: bytes | None) -> dict[str, Any]:
    """What yourdfpy reads from the URDF text for forward kinematics, as JSON-ready data, or
    ``{"error": why}`` when it cannot read it (the check then falls back to mjcfbuild's own
    parse and says so). Never raises."""
    if urdf is None:
        return {"error": "no URDF text given"}
    try:
        import numpy as np
        import yourdfpy  # numpy, trimesh, scipy: only where the reference is read

        loaded = yourdfpy.URDF.load(
            io.BytesIO(urdf),
            load_meshes=False,
            build_collision_scene_graph=False,
            load_collision_meshes=False,
        )
        joints = [
            {
                "name": joint.name,
                "type": joint.type,
                "parent": joint.parent,
                "child": joint.child,
                "origin": (np.eye(4) if joint.origin is None else joint.origin).tolist(),
                "axis": [float(v) for v in joint.axis] if joint.axis is not None else None,
                "mimic": None
                if joint.mimic is None
                else {
                    "joint": joint.mimic.joint,
                    "multiplier": float(joint.mimic.multiplier),
                    "offset": float(joint.mimic.offset),
                },
            }
            for joint in loaded.robot.joints
        ]
        return {
            "reader": READER,
            "base": loaded.base_link,
            "links": list(loaded.link_map),
            "actuated": list(loaded.actuated_joint_names),
            "joints": joints,
        }
    except Exception as exc:  # any reader failure: fall back, never fail the check for it
        return {"error": f"{READER} could not read the URDF ({type(exc).__name__}: {exc})"}


class ReferenceKinematics:
    """Link poses relative to the root link at given joint values, from a record of
    :func:`read_kinematics`, computed as yourdfpy computes them."""

    def __init__(self, record: dict[str, Any]) -> None:
        self.name: str = record["reader"]
        self.links: list[str] = list(record["links"])
        self._base: str = record["base"]
        self._actuated = set(record["actuated"])
        self._children: dict[str, list[dict]] = defaultdict(list)
        for joint in record["joints"]:
            self._children[joint["parent"]].append(joint)

    def poses(self, joint_values: dict[str, float]) -> dict[str, Transform]:
        """Every link's pose at ``joint_values`` (by joint name; mimic joints follow their
        leaders as the URDF says, whatever value they are given here)."""
        import numpy as np

        values = {name: joint_values.get(name, 0.0) for name in self._actuated}
        frames = {self._base: np.eye(4)}
        order = [self._base]
        for link in order:
            for joint in self._children.get(link, []):
                motion = _motion(joint, values)
                frames[joint["child"]] = frames[link] @ np.array(joint["origin"]) @ motion
                order.append(joint["child"])
        result = {}
        for link, matrix in frames.items():
            rotation: Matrix = tuple(  # type: ignore[assignment]
                tuple(float(v) for v in matrix[row, :3]) for row in range(3)
            )
            x, y, z = (float(v) for v in matrix[:3, 3])
            result[link] = Transform(rotation, (x, y, z))
        return result


def _motion(joint: dict, values: dict[str, float]) -> Any:
    """The joint's own motion at its value (4x4): a rotation about its unit axis or a
    translation along it; nothing for fixed, floating and planar joints. The axis is made a
    unit one for both, as KDL (robot_state_publisher, MoveIt) and MuJoCo do: yourdfpy
    scales a prismatic joint's travel by the length of the axis as written."""
    import numpy as np

    motion = np.eye(4)
    if joint["type"] not in MOVING:
        return motion
    mimic = joint["mimic"]
    if mimic is None:
        value = values.get(joint["name"], 0.0)
    elif mimic["joint"] in values:
        value = values[mimic["joint"]] * mimic["multiplier"] + mimic["offset"]
    else:  # yourdfpy: a mimic of a joint that is not actuated stays at its offset
        value = mimic["offset"]
    axis = np.array(joint["axis"], dtype=float)
    unit = axis / np.linalg.norm(axis)
    if joint["type"] == "prismatic":
        motion[:3, 3] = value * unit
        return motion
    cross = np.array([[0.0, -unit[2], unit[1]], [unit[2], 0.0, -unit[0]], [-unit[1], unit[0], 0.0]])
    motion[:3, :3] = (
        math.cos(value) * np.eye(3)
        + math.sin(value) * cross
        + (1.0 - math.cos(value)) * np.outer(unit, unit)
    )
    return motion


def reference_from_record(
    record: dict[str, Any] | None,
) -> tuple[ReferenceKinematics | None, str | None]:
    """The independent reference a record describes, or (None, why not)."""
    if record is None:
        return None, "no reference read"
    if "error" in record:
        return None, str(record["error"])
    try:
        return ReferenceKinematics(record), None
    except (KeyError, TypeError) as exc:
        return None, f"the reference record is incomplete ({exc})"
