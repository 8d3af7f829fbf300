"""The attributes MuJoCo's XML accepts on each element, read from the schema MuJoCo itself
prints (``mj_printSchema``), so that an input setting one MuJoCo does not have is an error at
the input's place rather than MuJoCo's "unrecognized attribute" about the assembled model.

The schema is a tree, one element a line (``camera (*)  axisangle class euler ...``, its
attributes wrapped onto the lines below, its children indented). An element of a body (a
``<joint>``, ``<geom>``, ``<camera>``) has the attributes it has there, not those of the
``<joint>`` of an equality or a tendon; any other has those of all its places.
"""

from __future__ import annotations

import re
from functools import lru_cache

# An element's line: its indentation, name (the world body is "(world)body"), how often it
# may appear, and the first of its attributes.
_ELEMENT = re.compile(r"^(?P<indent>\s*)(?:\(world\))?(?P<name>[a-z_]\w*) \([!?*R]\)(?P<words>.*)$")


@lru_cache(maxsize=1)
def _schema() -> tuple[dict[str, frozenset[str]], dict[str, frozenset[str]]]:
    """Each element's attributes in a body, and in all its places."""
    import mujoco

    in_body: dict[str, set[str]] = {}
    anywhere: dict[str, set[str]] = {}
    parents: list[tuple[int, str]] = []  # the elements above the current one, with their indent
    current: list[set[str]] = []
    for line in mujoco.mj_printSchema(False, False).splitlines():
        match = _ELEMENT.match(line)
        if match is not None:
            indent, name = len(match.group("indent")), match.group("name")
            while parents and parents[-1][0] >= indent:
                parents.pop()
            current = [anywhere.setdefault(name, set())]
            if name == "body" or any(parent == "body" for _, parent in parents):
                current.append(in_body.setdefault(name, set()))
            parents.append((indent, name))
            line = match.group("words")
        for attributes in current:
            attributes.update(line.split())
    return _frozen(in_body), _frozen(anywhere)


def _frozen(table: dict[str, set[str]]) -> dict[str, frozenset[str]]:
    return {name: frozenset(attributes) for name, attributes in table.items()}


def mujoco_attributes(element: str) -> frozenset[str]:
    """The attributes MuJoCo accepts on ``element``, in a body where it can be in one (empty
    for an element MuJoCo does not have)."""
    in_body, anywhere = _schema()
    return in_body.get(element) or anywhere.get(element, frozenset())


def mujoco_attributes_anywhere(element: str) -> frozenset[str]:
    """The attributes MuJoCo accepts on ``element`` in any of its places (empty for an
    element MuJoCo does not have): what raw MJCF, whose place this module does not follow,
    may set without being refused wrongly."""
    return _schema()[1].get(element, frozenset())


def mujoco_named_elements() -> frozenset[str]:
    """The MuJoCo elements that can have a name: what a modification's ``type`` may be."""
    return frozenset(
        element for element, attributes in _schema()[1].items() if "name" in attributes
    )
