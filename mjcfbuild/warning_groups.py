"""Warnings as the console shows them: one line per kind, with a count and the first subjects.

Build steps write warnings as plain sentences, one per joint, link or mesh they are about. Two
warnings are of one kind when they differ only in their variable parts: the ``file:line:`` they
start with, quoted names and values, and numbers. A kind seen once prints as it is. A kind seen
N times whose warnings differ in one part only (the subject: a link, a joint, a file) prints as
``N × <the sentence, '…' for the subject>: a, b, c, ...``; one whose warnings differ in more
than that (a name and its figures, a URI and its path) would read as a bare template there
(``'…' ('…')``, ``principal moments … … … -> … … …``), so it prints its first warning whole and
``(and N-1 more like it: b, c, d, ...)`` (each subject once, not the first's own; each one's
``file:line`` where only numbers vary; just ``(and N-1 more like it)`` where none is left to
list). Either keeps the first warning's location so an editor
can still jump to it. The report lists every warning.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

SHOWN_SUBJECTS = 3

# A location first: "file:line:" or "file:line:column:", or a file name with a suffix.
_LOCATION = re.compile(r"^(?P<where>[^\s:'\"]+:\d+(?::\d+)?|[^\s:'\"]+\.\w+): ")
_LINE = re.compile(r":\d+(?::\d+)?$")
# The parts of a sentence that name what it is about: quoted text and free-standing numbers.
_SLOT = re.compile(
    r"(?<!\w)'(?P<single>[^']*)'(?!\w)|\"(?P<double>[^\"]*)\"|"
    r"(?<![\w.+-])(?P<number>[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)(?![\w.])"
)


@dataclass
class _Kind:
    """Warnings whose sentences agree outside their slots."""

    pieces: tuple[str, ...]  # the text around the slots
    quoted: tuple[str, ...]  # each slot's quote character ("" for a number)
    texts: list[str] = field(default_factory=list)
    locations: list[str | None] = field(default_factory=list)
    slots: list[tuple[str, ...]] = field(default_factory=list)


def group_warnings(warnings: list[str], more: str = "", fewest: int = 2) -> list[str]:
    """One line per kind of warning, in the order each kind first appears.

    ``more`` follows the subjects of a kind that has more than are shown (where to find them
    all, like ``"see report/report.md"``). A kind with fewer than ``fewest`` warnings prints
    each as it is (the check's failures: their figures matter while they are few).
    """
    kinds: dict[tuple[tuple[str, ...], tuple[str, ...]], _Kind] = {}
    for text in dict.fromkeys(warnings):
        location, message = _split_location(text)
        pieces, quoted, values = _slots(message)
        kind = kinds.setdefault((pieces, quoted), _Kind(pieces, quoted))
        kind.texts.append(text)
        kind.locations.append(location)
        kind.slots.append(values)
    lines = []
    for kind in kinds.values():
        lines += [_line(kind, more)] if len(kind.texts) >= fewest else kind.texts
    return lines


def _split_location(text: str) -> tuple[str | None, str]:
    match = _LOCATION.match(text)
    if match is None:
        return None, text
    return match.group("where"), text[match.end() :]


def _slots(message: str) -> tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...]]:
    """The text between the slots, each slot's quote character, and each slot's value."""
    pieces, quoted, values = [], [], []
    start = 0
    for match in _SLOT.finditer(message):
        pieces.append(message[start : match.start()])
        if match.group("single") is not None:
            quoted.append("'")
            values.append(match.group("single"))
        elif match.group("double") is not None:
            quoted.append('"')
            values.append(match.group("double"))
        else:
            quoted.append("")
            values.append(match.group("number"))
        start = match.end()
    pieces.append(message[start:])
    return tuple(pieces), tuple(quoted), tuple(values)


def _line(kind: _Kind, more: str) -> str:
    if len(kind.texts) == 1:
        return kind.texts[0]
    columns = list(zip(*kind.slots, strict=True))
    varying = [len(set(column)) > 1 for column in columns]
    subjects = _subjects(kind, columns, varying)
    if sum(varying) + _files_vary(kind) > 1:
        return _first_and_more(kind, _subjects(kind, columns, varying, numbers=False), more)
    text = kind.pieces[0]
    for index, column in enumerate(columns):
        value = "…" if varying[index] else column[0]
        quote = kind.quoted[index]
        text += f"{quote}{value}{quote}{kind.pieces[index + 1]}"
    line = f"{len(kind.texts)} × {text.rstrip('.')}"
    shown = [subject for subject in dict.fromkeys(subjects) if subject]
    if len(shown) > 1:
        rest = len(shown) - SHOWN_SUBJECTS
        line += f": {', '.join(shown[:SHOWN_SUBJECTS])}" + (
            f", ... {rest} more" if rest > 0 else ""
        )
        if rest > 0 and more:
            line += f" ({more})"
    first = kind.locations[0]
    return f"{first}: {line}" if first is not None else line


def _first_and_more(kind: _Kind, subjects: list[str], more: str) -> str:
    """The first warning whole, then how many more of its kind there are and what they are
    about: ``<first> (and 4 more like it: b, c, d, ...; all in report.md)``. Each subject is
    listed once, never the first warning's own; where none is left to list (every subject
    empty, or the first's), ``<first> (and 4 more like it; all in report.md)``."""
    others = [s for s in dict.fromkeys(subjects[1:]) if s and s != subjects[0]]
    line = f"{kind.texts[0].rstrip('.')} (and {len(kind.texts) - 1} more like it"
    if not others:
        return line + (f"; {more}" if more else "") + ")"
    listed = ", ".join(others[:SHOWN_SUBJECTS])
    if len(others) > SHOWN_SUBJECTS:
        listed += ", ..." + (f"; {more}" if more else "")
    return f"{line}: {listed})"


def _files_vary(kind: _Kind) -> bool:
    """Whether each warning is about a file of its own: they start with different files and
    no line (a mesh's warnings), so the file is what they are about."""
    places = kind.locations
    return all(p is not None and not _LINE.search(p) for p in places) and len(set(places)) > 1


def _subjects(
    kind: _Kind, columns: list[tuple[str, ...]], varying: list[bool], numbers: bool = True
) -> list[str]:
    """What each warning of a kind is about: its file (where each names a file of its own),
    else its first varying quoted name, else its first varying value, else its location.
    Without ``numbers``, a varying number is not taken for the subject: listed apart from the
    sentence it varies in ("and 2 more like it: 3, 5"), a bare figure names nothing a user can
    find, so the location names each instead."""
    places = [location or "" for location in kind.locations]
    if _files_vary(kind):
        return places
    quoted_first = sorted(range(len(columns)), key=lambda i: (kind.quoted[i] == "", i))
    for index in quoted_first:
        if varying[index] and (numbers or kind.quoted[index]):
            quote = kind.quoted[index] or "'"
            return [
                f"{quote}{value}{quote}" if re.search(r"[\s,]", value) else value
                for value in columns[index]
            ]
    return places
