"""Refusing XML entity declarations before any parser sees them.

Entities are how "billion laughs" documents blow up memory and how external entities read files
or the network. Robot descriptions never need them, so any ``<!ENTITY`` declaration in a URDF,
xacro file (included ones too) or inputs file is an error rather than something to expand.
"""

from __future__ import annotations

import re

from mjcfbuild.errors import InputError

# What cannot declare anything: comments and CDATA sections (their text is inert).
_INERT = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>", re.DOTALL)


def refuse_entities(data: bytes, display_file: str) -> None:
    """Raise :class:`InputError` at the line of the first ``<!ENTITY`` declaration in ``data``
    (the words in a comment declare nothing: the xacro command reads such a file)."""
    entity = data.find(b"<!ENTITY")
    if entity >= 0:
        # Blanked, not removed: the positions, and so the lines, stay where they were.
        entity = blank_inert(data).find(b"<!ENTITY")
    if entity >= 0:
        raise InputError(
            "XML entity declarations are not allowed",
            file=display_file,
            line=data.count(b"\n", 0, entity) + 1,
            hint="robot descriptions do not need them; remove the <!ENTITY> declaration",
        )


def blank_inert(data: bytes) -> bytes:
    """``data`` with its comments and CDATA sections blanked: what they hold declares and
    instructs nothing. Blanked, not removed: the positions, and so the lines, stay."""
    return _INERT.sub(lambda inert: b" " * len(inert.group()), data)
