"""The model's arena, sized for its contacts where MuJoCo's default would not hold them.

MuJoCo keeps contacts and constraint rows in one arena whose size it guesses from the model
when ``<size memory>`` is not given. A long chain lying on the floor outgrows that guess (the
496-link snake: about 1,980 contacts, 48 MB by default, ``mj_stackAlloc: out of memory``
within 1 s of control). The bound here: every colliding geom in up to
:data:`CONTACTS_PER_GEOM` contacts (a box on a plane makes 4), each contact's constraint rows
(pyramidal cone: 2 (condim - 1)), each row costing :data:`BYTES_PER_ROW_DOF` per degree of
freedom, twice over. A model the default arena already holds gets no ``<size>``: its bytes
stay what they were.
"""

from __future__ import annotations

import math
from typing import Any

from lxml import etree

CONTACTS_PER_GEOM = 4
# Measured (MuJoCo 4.0): a 150-link chain on the floor under pseudorandom control used at
# most 8.26 MB for 596 contacts, 2,128 rows and 149 dofs: 26 bytes per row and dof.
BYTES_PER_ROW_DOF = 26
MARGIN = 2
MIB = 1 << 20


def arena_bytes(model: Any) -> int:
    """The arena ``model`` (a compiled ``MjModel``) needs for its contacts, by the bound
    above; 0 when nothing collides."""
    colliding = [
        geom
        for geom in range(model.ngeom)
        if model.geom_contype[geom] or model.geom_conaffinity[geom]
    ]
    if not colliding:
        return 0
    rows = max(max(1, 2 * (int(model.geom_condim[geom]) - 1)) for geom in colliding)
    contacts = CONTACTS_PER_GEOM * len(colliding)
    return contacts * rows * max(model.nv, 1) * BYTES_PER_ROW_DOF * MARGIN


def holds_contacts(model: Any) -> bool:
    """Whether the arena MuJoCo sized for ``model`` holds the bound above."""
    return arena_bytes(model) <= model.narena


def size_arena(root: etree._Element, model: Any) -> str | None:
    """Give ``root`` (the model ``model`` was compiled from) a ``<size memory>`` where the
    bound exceeds the arena MuJoCo sized by default; the value set, or None (a memory the
    user gave is left alone)."""
    size = root.find("size")
    if size is not None and size.get("memory") is not None:
        return None
    needed = arena_bytes(model)
    if needed <= model.narena:
        return None
    memory = f"{math.ceil(needed / MIB)}M"
    if size is None:
        size = etree.Element("size")
        anchor = root.find("option")
        if anchor is None:
            anchor = root.find("compiler")
        if anchor is not None:
            anchor.addnext(size)
        else:
            root.insert(0, size)
    size.set("memory", memory)
    return memory
