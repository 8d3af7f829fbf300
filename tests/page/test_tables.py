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


def test_the_script_holds_the_reports_tables_and_what_the_check_measured():
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
        "products": {"meshes": 3, "decompositions": 1},
        "previews": [],
    }
    hold = {"max_deviation": 0.01, "joint": "elbow", "floating": False, "base_tilt": None}
    report["check"] = {"hold": hold, "loads": True}
    tables, checked = tables_script(report).decode().splitlines()
    assert tables.startswith("window.MJCFBUILD_TABLES = ") and tables.endswith(";")
    html = json.loads(tables.removeprefix("window.MJCFBUILD_TABLES = ").rstrip(";"))
    assert checked == (
        'window.MJCFBUILD_CHECKED = {"hold": {"base_tilt": null, "failed": false, '
        '"floating": false, "held": 0, "joint": "elbow", "max_deviation": 0.01, "passive": 0, '
        '"passive_deviation": 0.0, "passive_joint": null, "passive_sags": false}};'
    )
    assert "<h2>arm: build report</h2>" in html
    assert "<p>3 mesh files converted, 1 collision mesh decomposed." in html
    assert "Local cache hits" not in html  # build-stats.json has where products came from
