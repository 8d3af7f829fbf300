"""The diff in the report page: the head revision's page (``output.page``) copied beside the
diff's Markdown, with the changes shown above its tables."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from mjcfbuild.diff.render import Sides

CHANGES_SCRIPT = "page/changes.js"
_VIEWER_TAG = '<script src="page/viewer.js"></script>'


def write_page(folder: Path, sides: Sides, markdown_text: str) -> bool:
    """Copy the head build's report page into ``folder`` (``index.html`` and ``page/``) with
    the diff's Markdown as a "Model changes" section; False where the head has no page."""
    from mjcfbuild.page.tables import markdown_html

    report = sides.head_folder / "report"
    index = report / "index.html"
    if not index.is_file() or not (report / "page").is_dir():
        return False
    target = folder / "page"
    if target.exists():
        shutil.rmtree(target)
    shutil.copytree(report / "page", target)
    script = f"window.MJCFBUILD_CHANGES = {json.dumps(markdown_html(markdown_text))};\n"
    (folder / CHANGES_SCRIPT).write_text(script)
    page = index.read_text()
    tag = f'<script src="{CHANGES_SCRIPT}"></script>\n'
    (folder / "index.html").write_text(page.replace(_VIEWER_TAG, tag + _VIEWER_TAG, 1))
    return True
