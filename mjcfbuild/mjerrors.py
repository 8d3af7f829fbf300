"""MuJoCo's errors about a model it cannot load, in one line of words.

MuJoCo reports XML its parser (tinyxml2) rejects as ``XML parse error 8:`` on the first line
and the reason and line on the second (``Error=XML_ERROR_PARSING_TEXT ErrorID=8 (0x8) Line
number=3``); its own XML errors name the element and line on the second line (``Element
'option', line 1``). A one-line message taken from the first line alone said nothing.
"""

from __future__ import annotations

import re

_PARSE = re.compile(r"Error=(XML_ERROR_\w+).*?Line number=(\d+)(?::\s*(.*))?")
_ELEMENT = re.compile(r"Element '(\w+)', line (\d+)")


def load_error(exc: BaseException) -> str:
    """What MuJoCo says about a model it cannot load, with the line where it says one."""
    lines = [line.strip() for line in str(exc).strip().splitlines() if line.strip()]
    if not lines:
        return type(exc).__name__
    rest = " ".join(lines[1:])
    parse = _PARSE.search(rest)
    if lines[0].startswith("XML parse error") and parse is not None:
        kind, line, detail = parse.groups()
        words = kind.removeprefix("XML_ERROR_").lower().replace("_", " ")
        return f"not well-formed XML at line {line} ({words}{': ' + detail if detail else ''})"
    element = _ELEMENT.search(rest)
    first = lines[0].removeprefix("XML Error: ").removeprefix("Error: ")
    if element is not None:
        return f"{first} (<{element.group(1)}> at line {element.group(2)})"
    return first
