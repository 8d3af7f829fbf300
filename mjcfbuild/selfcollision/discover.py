"""Finding a floating robot's standing pose in the SRDF its description ships, and picking it.

MoveIt configurations and many description packages keep an SRDF beside the URDF whose
``<group_state>`` poses include how the robot stands (``standing``, ``half_sitting``, ...). For
a floating robot with no SRDF named in robot.yaml, mjcfbuild looks for one:

- in the description's folder and the two folders above it: ``*.srdf``, ``srdf/*.srdf``,
  ``config/*.srdf``, and a sibling MoveIt package's ``*_moveit_config/config/*.srdf``;
- of several, the one whose name is the description's (``go1.urdf`` -> ``go1.srdf``), else
  the one sharing the longest start with it, else the first by name.

Only its poses are used (its ``<disable_collisions>`` count only for an SRDF named in
``self_collision.srdf``). The pose is the first group_state, in the order of
:data:`STANDING_NAMES`, whose name is or contains that word and whose joints are all the
robot's; the floating root joint MoveIt SRDFs list (a ``virtual_joint``, or a joint with a
7-number pose) is the free joint, and is left out.
"""

from __future__ import annotations

from pathlib import Path

# Names of standing poses, most specific first (matched exactly, then as a part of a name).
STANDING_NAMES = ("standing", "stand", "half_sitting", "home", "default", "ready", "neutral")
_PATTERNS = ("*.srdf", "srdf/*.srdf", "config/*.srdf")
_LEVELS = 3  # the description's folder and two above it


def find_srdf(source: Path) -> Path | None:
    """The SRDF that belongs to the description at ``source``, if one is found."""
    candidates = sorted(
        Path(found) for matched in srdf_searches(source).values() for found in matched
    )
    if not candidates:
        return None
    stem = _stem(source.name)
    return min(candidates, key=lambda path: (-_shared(stem, _stem(path.name)), str(path)))


def srdf_searches(source: Path) -> dict[str, list[str]]:
    """Where :func:`find_srdf` looks for the SRDF of the description at ``source``: each
    file-name pattern and the files it matches now. An SRDF that appears later changes a
    match, so a build that recorded these reruns (the no-op stamp checks them)."""
    import glob

    folders = [glob.escape(str(f)) for f in [source.parent, *source.parent.parents][:_LEVELS]]
    patterns = [f"{folder}/{pattern}" for folder in folders for pattern in _PATTERNS]
    if len(folders) == _LEVELS:
        patterns.append(f"{folders[-1]}/*_moveit_config/config/*.srdf")
    # glob's rules, as the stamp checks them again (a hidden .x.srdf is not looked at)
    return {pattern: sorted(glob.glob(pattern)) for pattern in patterns}


def standing_state(
    states: dict[str, dict[str, float]], joints: set[str], floating: set[str]
) -> str | None:
    """The name of the first of ``states`` that is a standing pose of a robot with
    ``joints`` (``floating``: root joint names to leave out), or None."""
    fitting = [
        name for name, values in states.items() if set(values) - floating <= joints and values
    ]
    for word in STANDING_NAMES:
        exact = [name for name in fitting if name.lower() == word]
        if exact:
            return exact[0]
    for word in STANDING_NAMES:
        containing = sorted(
            (name for name in fitting if word in name.lower()), key=lambda n: (len(n), n)
        )
        if containing:
            return containing[0]
    return None


def _stem(name: str) -> str:
    for suffix in (".xacro", ".urdf", ".srdf", ".xml"):
        name = name.removesuffix(suffix)
    return name.lower()


def _shared(first: str, second: str) -> int:
    """How many leading characters the names share (all of them counts one more)."""
    if first == second:
        return len(first) + 1
    count = 0
    for a, b in zip(first, second, strict=False):
        if a != b:
            break
        count += 1
    return count
