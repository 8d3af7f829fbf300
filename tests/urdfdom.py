"""ROS's URDF parser as a judge: Debian's ``liburdfdom-tools`` (``check_urdf``,
``urdf_to_graphviz``), the command line of the urdfdom library that robot_state_publisher,
MoveIt and rviz read URDF with.

:func:`urdfdom_read` runs both on a file and returns what urdfdom made of it: whether it
accepted it, the errors it logged (urdfdom logs some defects, drops the element and still
accepts the file), the root link, each link's children in urdfdom's order, and each joint's
parent, child and origin as ``urdf_to_graphviz`` prints them (six significant digits; the
rotation as urdfdom's quaternion turned back into roll, pitch, yaw). Tests that need it call
:func:`require_urdfdom`: skipped without the tools, failed in CI (``CI=true``).
"""

from __future__ import annotations

import math
import re
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from mjcfbuild.urdf.transforms import rotation_angle_between, rpy_to_matrix
from tests.executables import require

INSTALL = "no check_urdf on PATH (apt-get install liburdfdom-tools)"
_ERROR = re.compile(r"^Error:\s+(.*)$")
_WHERE = re.compile(r"^\s+at line (\d+) in (\S+)$")
_ROOT = re.compile(r"^root Link: (.*) has \d+ child\(ren\)$")
_CHILD = re.compile(r"^((?:    )+)child\(\d+\):  (.*)$")
_JOINT = re.compile(r'^"(.*)" -> "(.*)" \[label="xyz: (.*) \\nrpy: (.*)"\]$')
_EDGE = re.compile(r'^"(.*)" -> "(.*)"$')


@dataclass(frozen=True)
class UrdfdomJoint:
    """A joint as urdfdom read it."""

    parent: str
    child: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]


@dataclass
class UrdfdomModel:
    """What urdfdom made of one URDF file."""

    accepted: bool
    errors: list[str]
    root: str | None = None
    children: dict[str, list[str]] = field(default_factory=dict)
    joints: dict[str, UrdfdomJoint] = field(default_factory=dict)

    def links(self) -> set[str]:
        """Every link of the tree."""
        return set(self.children) | {c for kids in self.children.values() for c in kids}


def find_check_urdf() -> str | None:
    """``check_urdf`` on PATH (with ``urdf_to_graphviz`` beside it), or None."""
    found = shutil.which("check_urdf")
    if found is None or not (Path(found).parent / "urdf_to_graphviz").exists():
        return None
    return found


def require_urdfdom() -> str:
    """``check_urdf`` for a test; without it the test is skipped, or fails in CI."""
    return require(find_check_urdf(), INSTALL)


def urdfdom_read(urdf: Path, scratch: Path) -> UrdfdomModel:
    """Run ``check_urdf`` and (when it accepts) ``urdf_to_graphviz`` on ``urdf``; ``scratch``
    is a folder for the graph file."""
    check_urdf = require_urdfdom()
    checked = subprocess.run(
        [check_urdf, str(urdf)], capture_output=True, text=True, errors="replace", check=False
    )
    text = checked.stdout + checked.stderr
    model = UrdfdomModel(accepted=checked.returncode == 0, errors=_errors(text))
    if not model.accepted:
        return model
    model.root, model.children = _tree(checked.stdout)
    scratch.mkdir(parents=True, exist_ok=True)
    graphviz = str(Path(check_urdf).parent / "urdf_to_graphviz")
    # An empty PATH: the tool's own call of graphviz's `dot` (to draw a PDF) finds nothing.
    subprocess.run(
        [graphviz, str(urdf.resolve()), "tree"],
        cwd=scratch,
        env={"PATH": ""},
        capture_output=True,
        check=True,
    )
    model.joints = _joints((scratch / "tree.gv").read_text(encoding="utf-8"))
    return model


def _errors(text: str) -> list[str]:
    """Each logged error as one line: its message and where in urdfdom's sources."""
    result: list[str] = []
    lines = text.splitlines()
    for index, line in enumerate(lines):
        found = _ERROR.match(line)
        if found is None:
            continue
        where = _WHERE.match(lines[index + 1]) if index + 1 < len(lines) else None
        suffix = f" ({where.group(2)}:{where.group(1)})" if where else ""
        result.append(found.group(1).strip() + suffix)
    return result


def _tree(stdout: str) -> tuple[str | None, dict[str, list[str]]]:
    """The root and each link's children from check_urdf's indented tree."""
    root = None
    children: dict[str, list[str]] = {}
    path: list[str] = []
    for line in stdout.splitlines():
        if (found := _ROOT.match(line)) is not None:
            root = found.group(1)
            children[root] = []
            path = [root]
        elif (found := _CHILD.match(line)) is not None and root is not None:
            depth = len(found.group(1)) // 4
            name = found.group(2)
            del path[depth:]
            children[path[-1]].append(name)
            children.setdefault(name, [])
            path.append(name)
    return root, children


def _joints(graph: str) -> dict[str, UrdfdomJoint]:
    """Each joint's parent, child and origin from urdf_to_graphviz's graph."""
    half: dict[str, tuple[str, tuple[float, float, float], tuple[float, float, float]]] = {}
    result: dict[str, UrdfdomJoint] = {}
    for line in graph.splitlines():
        if (found := _JOINT.match(line)) is not None:
            parent, joint, xyz, rpy = found.groups()
            half[joint] = (parent, _floats(xyz), _floats(rpy))
        elif (found := _EDGE.match(line)) is not None and found.group(1) in half:
            parent, xyz, rpy = half.pop(found.group(1))
            result[found.group(1)] = UrdfdomJoint(parent, found.group(2), xyz, rpy)
    return result


def _floats(text: str) -> tuple[float, float, float]:
    x, y, z = (float(part) for part in text.split())
    return x, y, z


def same_origin(
    joint: UrdfdomJoint, xyz: tuple[float, float, float], rpy: tuple[float, float, float]
) -> bool:
    """Whether an origin agrees with urdfdom's to the six digits it prints: the same
    translation and the same rotation (roll, pitch, yaw are not unique)."""
    near = all(
        math.isclose(a, b, rel_tol=2e-5, abs_tol=1e-5) for a, b in zip(joint.xyz, xyz, strict=True)
    )
    turn = rotation_angle_between(rpy_to_matrix(joint.rpy), rpy_to_matrix(rpy))
    return near and turn < 1e-4
