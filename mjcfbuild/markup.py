"""Names and messages written into Markdown, HTML or XML: one escaping function per format.

Robot descriptions name links, joints, meshes and files freely, so a name may hold anything
Markdown or HTML reads as markup: ``![x](http://host/leak.png)`` would become a picture that
a browser fetches, ``a|b`` another table column, ``<img onerror=...>`` a tag. Everything
mjcfbuild writes into ``report.md``, the package README and CHANGELOG, ``mjcfbuild diff``'s
Markdown and the report page's HTML goes through these functions, which make any text read as
the text it is (docs/page.md, "Names").
"""

from __future__ import annotations

import html
import re
from collections.abc import Mapping
from urllib.parse import quote

# Characters that start or end Markdown (CommonMark and GitHub's tables, strikethrough and
# maths) wherever they stand; a backslash before any of them makes it a plain character.
# Every link, picture and footnote opens with a "[", every tag and autolink with a "<", so
# "]" and ">" can stay bare: "[-1 1] -> [0 1]" reads "\[-1 1] -> \[0 1]".
_ALWAYS = frozenset("\\`*[<|~&#$")
# Where a text starts a line these begin a quote, a heading rule, a thematic break, or a list
# (a bullet or "1." only when a space or the end follows: "1.5" and "-0.3" read as numbers).
_LEADING = re.compile(r"^(?:[>=]|(?:[-+]|\d+[.)])(?=\s|$)|-(?=-))")
_BREAKS = re.compile(r"[\r\n\t\f\v]")


def markdown_text(value: object) -> str:
    """``value`` as plain text in Markdown: in a paragraph, a list item, a heading or a table
    cell it reads as itself. An underscore after a letter or digit stays bare (CommonMark
    never opens emphasis there, and every other one is escaped, so none can be closed), so
    ``left_hip_joint`` and ``hand_`` still read well in the raw file."""
    text = _BREAKS.sub(" ", str(value))
    out: list[str] = []
    for index, char in enumerate(text):
        if char in _ALWAYS or (char == "_" and not (index and text[index - 1].isalnum())):
            out.append("\\" + char)
        else:
            out.append(char)
    escaped = "".join(out)
    leading = _LEADING.match(escaped)
    if leading:
        end = leading.end()
        escaped = escaped[: end - 1] + "\\" + escaped[end - 1 :]
    return escaped


def markdown_code(value: object) -> str:
    """``value`` as a Markdown code span, fenced by more backticks than it holds in a row.
    Not for table cells, where a ``|`` would still end the cell: use :func:`markdown_text`."""
    text = _BREAKS.sub(" ", str(value))
    fence = "`" * (_longest_run(text, "`") + 1)
    padded = f" {text} " if text.startswith("`") or text.endswith("`") else text
    return f"{fence}{padded}{fence}"


def markdown_block(value: object, language: str = "") -> list[str]:
    """``value`` as the lines of a fenced code block, its fence longer than any run of
    backticks in it."""
    text = str(value).rstrip("\n")
    fence = "`" * max(3, _longest_run(text, "`") + 1)
    return [f"{fence}{language}", *text.split("\n"), fence]


def markdown_target(path: str) -> str:
    """A relative file path as a Markdown link or picture destination, percent-encoded so that
    spaces, parentheses and brackets in it cannot end it."""
    return quote(path, safe="/")


def html_text(value: object) -> str:
    """``value`` as HTML text or an attribute value (quotes escaped too)."""
    return html.escape(str(value), quote=True)


def _longest_run(text: str, char: str) -> int:
    runs = re.findall(f"{re.escape(char)}+", text)
    return max((len(run) for run in runs), default=0)


def xml_text(value: str, entities: Mapping[str, str] | None = None) -> str:
    """``value`` as XML character data: ``&``, ``>`` and ``<`` escaped, then each key of
    ``entities`` replaced by its value (what ``xml.sax.saxutils.escape`` writes, without the
    0.01 s of urllib, http and ssl that module imports)."""
    text = value.replace("&", "&amp;").replace(">", "&gt;").replace("<", "&lt;")
    for key, entity in (entities or {}).items():
        text = text.replace(key, entity)
    return text


def xml_attribute(value: str) -> str:
    """``value`` as a quoted XML attribute value: in double quotes, in single quotes where it
    holds a double quote and no single one, else with ``&quot;``; line breaks and tabs as
    character references (what ``xml.sax.saxutils.quoteattr`` writes)."""
    text = xml_text(value, {"\n": "&#10;", "\r": "&#13;", "\t": "&#9;"})
    if '"' not in text:
        return f'"{text}"'
    if "'" not in text:
        return f"'{text}'"
    return '"' + text.replace('"', "&quot;") + '"'
