"""Names in Markdown and HTML read as the text they are (mjcfbuild.markup)."""

from __future__ import annotations

import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from mjcfbuild.markup import (
    html_text,
    markdown_block,
    markdown_code,
    markdown_target,
    markdown_text,
    xml_attribute,
    xml_text,
)
from mjcfbuild.page.tables import markdown_html
from tests.page.hostile import NAMES, cells, markup_outside_code, unescaped

MORE = (
    "*em* _em_ __strong__ ~~gone~~ $x$",
    "# heading",
    "- item",
    "+ item",
    "12. item",
    "> quote",
    "<http://127.0.0.1:8765/autolink>",
    "[link](http://127.0.0.1:8765/)",
    "&amp; &#60;",
    "back\\slash\\",
    "line\nbreak\ttab",
    "``double`` `single`",
)


@pytest.mark.parametrize("name", [*NAMES, *MORE])
def test_a_name_in_a_table_cell_is_one_cell_of_its_own_text(name):
    row = f"| {markdown_text(name)} | {markdown_text(name)} |"
    flat = name.replace("\n", " ").replace("\t", " ")
    assert cells(row) == [flat, flat]
    assert markup_outside_code(row) == []
    html = markdown_html(f"| a | b |\n|---|---|\n{row}\n")
    assert html.count("<td>") == 2 and "<img" not in html and "<a" not in html
    assert f"<td>{html_text(flat)}</td>" in html


@pytest.mark.parametrize("name", [*NAMES, *MORE])
def test_a_name_alone_in_a_paragraph_or_list_item_is_text(name):
    text = markdown_text(name)
    assert not re.match(r"([#+>*=-]|\d+[.)])", text)  # no heading, list, quote or rule
    flat = name.replace("\n", " ").replace("\t", " ")
    assert unescaped(text) == flat
    assert markdown_html(f"- {text}\n") == f"<ul><li>{html_text(flat)}</li></ul>\n"
    assert markdown_html(f"{text}\n") == f"<p>{html_text(flat)}</p>\n"


def test_underscores_after_a_letter_stay_bare_for_people_reading_the_file():
    assert markdown_text("left_hip_joint") == "left_hip_joint"
    assert markdown_text("hand_") == "hand_"
    assert markdown_text("_private_ _x") == "\\_private_ \\_x"  # no emphasis can open


@pytest.mark.parametrize("name", ["plain", "j|`code`", "`start", "end`", "``two``"])
def test_a_code_span_holds_any_backticks(name):
    span = markdown_code(name)
    assert markdown_html(f"x {span}\n") == f"<p>x <code>{html_text(name)}</code></p>\n"


def test_a_code_block_is_fenced_longer_than_what_it_holds():
    lines = markdown_block('<exclude body1="a```b"/>', "xml")
    assert lines == ["````xml", '<exclude body1="a```b"/>', "````"]
    html = markdown_html("\n".join(lines) + "\n")
    assert html == "<pre><code>&lt;exclude body1=&quot;a```b&quot;/&gt;</code></pre>\n"


def test_a_picture_is_drawn_only_from_a_file_beside_the_page():
    assert markdown_html("![side](previews/side%20view.png)\n") == (
        '<img alt="side" src="previews/side%20view.png">\n'
    )
    for address in ("http://127.0.0.1:8765/x.png", "//host/x.png", "/etc/x.png", "data:x"):
        html = markdown_html(f"![x]({address})\n| ![y]({address}) |\n")
        assert "<img" not in html, html


def test_a_file_path_is_a_picture_address_whatever_its_name():
    assert markdown_target("tuning/a (b) [c].png") == "tuning/a%20%28b%29%20%5Bc%5D.png"


@given(st.text())
def test_xml_escaping_writes_what_the_standard_library_writes(text):
    from xml.sax.saxutils import escape, quoteattr

    assert xml_text(text) == escape(text)
    assert xml_text(text, {'"': "&quot;"}) == escape(text, {'"': "&quot;"})
    assert xml_attribute(text) == quoteattr(text)


@pytest.mark.parametrize("text", ['a"b', "a'b", "a'\"b", "x\n\ty", "<&>"])
def test_xml_attributes_choose_their_quotes_as_the_standard_library_does(text):
    from xml.sax.saxutils import quoteattr

    assert xml_attribute(text) == quoteattr(text)
