"""The interactive report page (``report/index.html``, ``output.page: true``).

``vendor`` fetches MuJoCo's WebAssembly build from npm into the user cache, ``bundle`` turns it
and the model's files into scripts a page opened from ``file://`` can load, ``tables`` renders
the report's tables, and ``web/`` holds the page's HTML, script and style.
"""

from __future__ import annotations

from pathlib import Path

WEB = Path(__file__).parent / "web"
WEB_FILES = ("index.html", "viewer.js", "page.css")  # the page's own files, package data


def web_files() -> list[Path]:
    """The page's template, script and style (file dependencies of the page task)."""
    return [WEB / name for name in WEB_FILES]
