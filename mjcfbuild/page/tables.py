"""The report's tables for the page: ``report.md``'s Markdown (mjcfbuild.check.report_page)
turned into HTML, and ``mjcfbuild diff``'s (mjcfbuild.diff.render). Only what those write is
understood: headings, pipe tables, bullet lists, fenced code, pictures, paragraphs, bold,
inline code and backslash escapes (mjcfbuild.markup). Every character of text reaches the HTML
escaped, and a picture is drawn only from a relative path: the page fetches nothing else.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from dataclasses import asdict

from mjcfbuild.markup import html_text

_IMAGE = re.compile(r"^!\[((?:\\.|[^\\\]])*)\]\(([^)\s]+)\)$")
_IMAGE_INLINE = re.compile(r"!\[((?:\\.|[^\\\]])*)\]\(([^)\s]+)\)")
_FENCE = re.compile(r"^(`{3,})")
_SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
_PUNCTUATION = frozenset("!\"#$%&'()*+,-./:;<=>?@[\\]^_`{|}~")


def markdown_html(text: str) -> str:
    """HTML for the Markdown ``report_page.markdown`` writes."""
    out: list[str] = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        line = lines[index].rstrip()
        fence = _FENCE.match(line)
        if fence:
            index += 1
            block = []
            while index < len(lines) and lines[index].rstrip() != fence.group(1):
                block.append(html_text(lines[index]))
                index += 1
            index += 1
            out.append("<pre><code>" + "\n".join(block) + "</code></pre>")
            continue
        if line.startswith("|"):
            rows = []
            while index < len(lines) and lines[index].startswith("|"):
                rows.append(lines[index].rstrip())
                index += 1
            out.append(_table(rows))
            continue
        if line.startswith("- "):
            items = []
            while index < len(lines) and lines[index].startswith("- "):
                items.append(f"<li>{_inline(lines[index][2:])}</li>")
                index += 1
            out.append("<ul>" + "".join(items) + "</ul>")
            continue
        index += 1
        heading = len(line) - len(line.lstrip("#"))
        image = _IMAGE.match(line)
        if not line:
            continue
        if 0 < heading <= 6 and line[heading : heading + 1] == " ":
            out.append(f"<h{heading + 1}>{_inline(line[heading + 1 :])}</h{heading + 1}>")
        elif image:
            out.append(_picture(*image.groups()))
        else:
            out.append(f"<p>{_inline(line)}</p>")
    return "\n".join(out) + "\n"


def _cells(row: str) -> list[str]:
    """A table row's cells; ``\\|`` is a ``|`` inside a cell."""
    body = row.strip()
    body = body[1:] if body.startswith("|") else body
    if body.endswith("|") and not body.endswith("\\|"):
        body = body[:-1]
    cells, current, index = [], [], 0
    while index < len(body):
        if body[index] == "\\" and index + 1 < len(body):
            current.append(body[index : index + 2])
            index += 2
            continue
        if body[index] == "|":
            cells.append("".join(current).strip())
            current = []
        else:
            current.append(body[index])
        index += 1
    cells.append("".join(current).strip())
    return cells


def _table(rows: list[str]) -> str:
    """A pipe table; its second row's colons say which columns are right-aligned."""
    head = _cells(rows[0])
    rule = _cells(rows[1]) if len(rows) > 1 else []
    right = [cell.endswith(":") for cell in rule]
    body = rows[2:] if rule and set("".join(rule)) <= set("-:") else rows[1:]

    def cell(tag: str, column: int, text: str) -> str:
        align = ' class="num"' if column < len(right) and right[column] else ""
        return f"<{tag}{align}>{_inline(text)}</{tag}>"

    parts = ["<table><thead><tr>"]
    parts += [cell("th", n, text) for n, text in enumerate(head)]
    parts.append("</tr></thead><tbody>")
    for row in body:
        parts.append("<tr>" + "".join(cell("td", n, t) for n, t in enumerate(_cells(row))))
        parts.append("</tr>")
    parts.append("</tbody></table>")
    return "".join(parts)


def _inline(text: str) -> str:
    """A line's inline Markdown as HTML: escapes, code spans, bold and pictures."""
    out: list[str] = []
    index = 0
    while index < len(text):
        char = text[index]
        if char == "\\" and index + 1 < len(text) and text[index + 1] in _PUNCTUATION:
            out.append(html_text(text[index + 1]))
            index += 2
        elif char == "`":
            index = _code_span(text, index, out)
        elif text.startswith("**", index) and (end := _unescaped(text, "**", index + 2)) > 0:
            out.append(f"<strong>{_inline(text[index + 2 : end])}</strong>")
            index = end + 2
        elif text.startswith("![", index) and (image := _IMAGE_INLINE.match(text, index)):
            out.append(_picture(*image.groups()))
            index = image.end()
        else:
            out.append(html_text(char))
            index += 1
    return "".join(out)


def _code_span(text: str, start: int, out: list[str]) -> int:
    """A code span opening at ``start`` (its content literal) into ``out``; where to go on."""
    run = len(text) - start - len(text[start:].lstrip("`"))
    fence = "`" * run
    search = start + run
    while (end := text.find(fence, search)) >= 0:
        if text[end + run : end + run + 1] != "`":  # a run of exactly the fence's length
            content = text[start + run : end]
            if content.startswith(" ") and content.endswith(" ") and content.strip():
                content = content[1:-1]
            out.append(f"<code>{html_text(content)}</code>")
            return end + run
        search = end + len(text[end:]) - len(text[end:].lstrip("`"))
    out.append(html_text(fence))  # no closing fence: the backticks are text
    return start + run


def _unescaped(text: str, marker: str, start: int) -> int:
    """Where ``marker`` next stands in ``text`` from ``start``, not after a backslash; -1."""
    index = start
    while index < len(text):
        if text[index] == "\\":
            index += 2
            continue
        if text.startswith(marker, index):
            return index
        index += 1
    return -1


def _picture(alt: str, src: str) -> str:
    """A picture from a file beside the page; any other address stays text, fetching nothing."""
    if _SCHEME.match(src) or src.startswith(("/", "\\")):
        return html_text(f"[{_plain(alt)}]")
    return f'<img alt="{html_text(_plain(alt))}" src="{html_text(src)}">'


def _plain(text: str) -> str:
    """Markdown text without its backslash escapes."""
    return re.sub(r"\\([!-/:-@\[-`{-~])", r"\1", text)


def tables_script(report: dict, place: Callable[[str], str] = str) -> bytes:
    """The report's tables as ``window.MJCFBUILD_TABLES`` (HTML), for the page: the same
    bytes for the same report (build times and cache counters are not in it); ``place``
    names a URDF line as report.md does (:func:`mjcfbuild.check.report_page.markdown`)."""
    from mjcfbuild.check.report_page import markdown
    from mjcfbuild.check.results import CheckResults

    text = markdown(report, place)
    checked = report.get("check")
    results = CheckResults.from_dict(checked) if checked else CheckResults()
    # What the build's check measured, which the page shows beside what the browser measures.
    measured: dict[str, object] = {}
    if results.hold:
        measured["hold"] = asdict(results.hold)
    if results.stand:
        measured["stand"] = results.stand.to_dict()
    if results.needs_controller:
        measured["needs_controller"] = results.needs_controller
    return (
        f"window.MJCFBUILD_TABLES = {json.dumps(markdown_html(text))};\n"
        f"window.MJCFBUILD_CHECKED = {json.dumps(measured, sort_keys=True)};\n"
    ).encode()
