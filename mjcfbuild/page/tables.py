"""The report's tables for the page: ``report.md``'s Markdown (mjcfbuild.check.report_page)
turned into HTML, and ``mjcfbuild diff``'s (mjcfbuild.diff.render). Only what those write is
understood: headings, pipe tables, bullet lists, pictures, paragraphs, bold and inline code.
"""

from __future__ import annotations

import html
import json
import re

_IMAGE = re.compile(r"^!\[([^\]]*)\]\(([^)]+)\)$")
_CODE = re.compile(r"`([^`]+)`")
_BOLD = re.compile(r"\*\*([^*]+)\*\*")
_INLINE_IMAGE = re.compile(r"!\[([^\]]*)\]\(([^)\s]+)\)")


def markdown_html(text: str) -> str:
    """HTML for the Markdown ``report_page.markdown`` writes."""
    out: list[str] = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        line = lines[index].rstrip()
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
            alt, src = (html.escape(part, quote=True) for part in image.groups())
            out.append(f'<img alt="{alt}" src="{src}">')
        else:
            out.append(f"<p>{_inline(line)}</p>")
    return "\n".join(out) + "\n"


def _cells(row: str) -> list[str]:
    return [cell.strip() for cell in row.strip().strip("|").split("|")]


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
    escaped = _CODE.sub(r"<code>\1</code>", html.escape(text, quote=True))
    escaped = _BOLD.sub(r"<strong>\1</strong>", escaped)
    return _INLINE_IMAGE.sub(r'<img alt="\1" src="\2">', escaped)


def tables_script(report: dict) -> bytes:
    """The report's tables as ``window.MJCFBUILD_TABLES`` (HTML), for the page. Build times
    and cache figures are left out: they differ from run to run, the model's tables do not."""
    from mjcfbuild.check.report_page import markdown

    text = markdown({**report, "times": {}, "cache": None})
    check = report.get("check") or {}
    # What the build's check measured, which the page shows beside what the browser measures.
    measured = {key: check[key] for key in ("hold", "stand", "needs_controller") if key in check}
    return (
        f"window.MJCFBUILD_TABLES = {json.dumps(markdown_html(text))};\n"
        f"window.MJCFBUILD_CHECKED = {json.dumps(measured, sort_keys=True)};\n"
    ).encode()
