"""``mjcfbuild diff --write``: where the new side has its report page, the diff is shown in it,
above the report's tables (opened in a real headless Chromium)."""

from __future__ import annotations

import shutil

from tests.conftest import run_cli
from tests.page.chromium import Browser, require_chromium
from tests.steps.test_page import build_with_page


def test_the_diff_is_shown_in_the_new_sides_report_page(tmp_path):
    new = build_with_page(tmp_path / "arm", "arm")
    old = tmp_path / "old"
    shutil.copytree(new, old)
    manifest = new.parent / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("elbow: 1.2", "elbow: 1.0"))
    assert run_cli("build", cwd=new.parent).code == 0
    out = tmp_path / "review"
    result = run_cli("diff", "--folders", str(old), str(new), "--write", str(out))
    assert result.code == 0, result.stderr
    assert (out / "index.html").is_file() and (out / "page" / "changes.js").is_file()
    assert "page/changes.js" in (out / "index.html").read_text()
    assert (new / "report" / "index.html").read_text().count("changes.js") == 0  # untouched

    browser = Browser(require_chromium())
    try:
        assert browser.open(out / "index.html") == "ready"
        changes = browser.evaluate("document.getElementById('changes').textContent")
        tables = browser.evaluate("document.getElementById('report').textContent")
    finally:
        browser.close()
    assert "Model changes" in changes and "elbow" in changes
    assert "1.2" in changes and "1" in changes
    assert "Actuators" in tables  # the report's own tables are still there, below
