"""The report's Markdown as the page's HTML tables."""

from __future__ import annotations

import json

from mjcfbuild.page.tables import markdown_html, tables_script


def test_headings_tables_lists_pictures_and_code():
    text = "\n".join(
        [
            "# arm: build report",
            "",
            "Model `arm.xml` <b>",
            "",
            "| joint | kp |",
            "|---|---:|",
            "| elbow | 181.9 |",
            "",
            "- a warning",
            "- another",
            "",
            "![side visual](previews/side_visual.png)",
        ]
    )
    assert markdown_html(text).splitlines() == [
        "<h2>arm: build report</h2>",
        "<p>Model <code>arm.xml</code> &lt;b&gt;</p>",
        '<table><thead><tr><th>joint</th><th class="num">kp</th></tr></thead><tbody>'
        '<tr><td>elbow</td><td class="num">181.9</td></tr></tbody></table>',
        "<ul><li>a warning</li><li>another</li></ul>",
        '<img alt="side visual" src="previews/side_visual.png">',
    ]


def test_the_script_leaves_out_what_changes_from_run_to_run():
    report = {
        "robot": "arm",
        "model": "arm.xml",
        "scene": "scene.xml",
        "bodies": 2,
        "geoms": 3,
        "assets": [],
        "check": {},
        "repairs": [],
        "warnings": [],
        "times": {"check": 0.95},
        "cache": {"computed": {}, "local_hits": 4},
        "previews": [],
    }
    report["check"] = {"hold": {"max_deviation": 0.01, "joint": "elbow"}, "loads": True}
    tables, checked = tables_script(report).decode().splitlines()
    assert tables.startswith("window.MJCFBUILD_TABLES = ") and tables.endswith(";")
    html = json.loads(tables.removeprefix("window.MJCFBUILD_TABLES = ").rstrip(";"))
    assert checked == (
        'window.MJCFBUILD_CHECKED = {"hold": {"joint": "elbow", "max_deviation": 0.01}};'
    )
    assert "<h2>arm: build report</h2>" in html
    assert "Build times" not in html and "Local cache hits" not in html
