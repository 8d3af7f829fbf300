"""``mjcfbuild diff``'s Markdown: names stay text, table rows keep their columns."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.diff.compare import Change, ModelDiff
from mjcfbuild.diff.render import Sides, markdown
from mjcfbuild.markup import html_text
from mjcfbuild.page.tables import markdown_html
from tests.page.hostile import CODE, NAMES, PICTURE, PIPES, TAG, markup_outside_code, tables


def test_names_in_the_diff_stay_text_and_in_their_cells():
    diff = ModelDiff()
    diff.add("structure", Change(PICTURE, "added", None, {"parent": PIPES}))
    diff.add("joints", Change(TAG, "range", [-1.0, 1.0], [-2.0, 2.0], note=CODE))
    diff.add("previews", Change(f"{PIPES}.png", "changed", None, None))
    sides = Sides(f"main{CODE}", "HEAD", Path("a"), Path("b"), PICTURE)
    text = markdown(diff, sides, {f"{PIPES}.png": f"previews/{PIPES}.png"})
    assert markup_outside_code(text.replace("(previews/a%7Cb.png)", "")) == []
    rows = [row for table in tables(text) for row in table]
    assert {len(row) for row in rows} == {5}
    assert {PICTURE, TAG, CODE} <= {cell for row in rows for cell in row}
    assert "parent a|b" in {cell for row in rows for cell in row}
    html = markdown_html(text)
    assert '<img alt="a|b.png: before, after" src="previews/a%7Cb.png">' in html
    assert html.count("<img") == 1 and "<a " not in html  # the picture of the preview only
    assert all(html_text(name) in html for name in NAMES)


def test_a_renamed_robot_names_both_model_files():
    """A rename said only the new name, over 'no model changes', as if nothing had happened."""
    import json

    from mjcfbuild.diff.render import as_json, text

    sides = Sides("HEAD~1", "working tree", Path("a"), Path("b"), "arm_v2.xml", "example_arm.xml")
    assert text(ModelDiff(), sides).splitlines() == [
        "mjcfbuild diff: example_arm.xml -> arm_v2.xml (renamed): HEAD~1 -> working tree",
        "no model changes",
    ]
    assert markdown(ModelDiff(), sides).startswith(
        "### Model changes: `example_arm.xml -> arm_v2.xml (renamed)`"
    )
    data = json.loads(as_json(ModelDiff(), sides))
    assert (data["base_model"], data["model"]) == ("example_arm.xml", "arm_v2.xml")
    same = Sides("HEAD~1", "working tree", Path("a"), Path("b"), "arm.xml", "arm.xml")
    assert text(ModelDiff(), same).startswith("mjcfbuild diff: arm.xml: HEAD~1")
