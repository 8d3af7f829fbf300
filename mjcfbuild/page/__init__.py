"""The interactive report page (``report/index.html``, ``output.page: true``).

``vendor`` fetches MuJoCo's WebAssembly build from npm into the user cache, ``compat`` adapts
the model to that older MuJoCo, ``bundle`` turns both into scripts a page opened from
``file://`` can load, ``tables`` renders the report's tables, and ``web/`` holds the page's
HTML, script and style. The step is mjcfbuild.steps.page; docs/page.md describes the page.
"""

from __future__ import annotations

from pathlib import Path

WEB = Path(__file__).parent / "web"
WEB_FILES = ("index.html", "viewer.js", "page.css")  # the page's own files, package data


def web_files() -> list[Path]:
    """The page's template, script and style (file dependencies of the page task)."""
    return [WEB / name for name in WEB_FILES]
