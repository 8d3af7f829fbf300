"""Refusing XML entity declarations before any parser sees them.

Entities are how "billion laughs" documents blow up memory and how external entities read files
or the network. Robot descriptions never need them, so any ``<!ENTITY`` declaration in a URDF,
xacro file (included ones too) or inputs file is an error rather than something to expand.
"""

from __future__ import annotations

from mjcfbuild.errors import InputError


def refuse_entities(data: bytes, display_file: str) -> None:
    """Raise :class:`InputError` at the line of the first ``<!ENTITY`` declaration in ``data``."""
    entity = data.find(b"<!ENTITY")
    if entity >= 0:
        raise InputError(
            "XML entity declarations are not allowed",
            file=display_file,
            line=data.count(b"\n", 0, entity) + 1,
            hint="robot descriptions do not need them; remove the <!ENTITY> declaration",
        )
