"""A robot whose names look like Markdown and HTML, and a reading of Markdown as CommonMark
and GitHub read it, for the tests that its names stay text in the report, the page, the
package and the diff."""

from __future__ import annotations

import itertools
import re
from pathlib import Path
from xml.sax.saxutils import quoteattr

from tests.conftest import run_cli
from tests.meshes.samples import ascii_stl

LEAK = "http://127.0.0.1:8765"
PICTURE = f"![x]({LEAK}/leak.png)"
TAG = f"<img src=x onerror=\"fetch('{LEAK}/xss')\">"
PIPES = "a|b"
CODE = "j|`code`|**bold**"
MESH = "m|![m](http:leak.png)<b>.stl"  # a mesh file name: no slash in it
NAMES = (PICTURE, TAG, PIPES, CODE)  # links PICTURE and PIPES, joints TAG and CODE

_MASS = (
    '<inertial><origin xyz="0 0 0.1"/><mass value="0.5"/>'
    '<inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>'
)


def hostile_urdf() -> str:
    """Two hinges in a row; one origin written with commas, so that the build warns and
    quotes the element (``<origin xyz=...>``) in its warning."""
    picture, pipes, tag, code = (quoteattr(n) for n in (PICTURE, PIPES, TAG, CODE))
    box = '<geometry><box size="0.05 0.05 0.2"/></geometry>'
    return f"""<?xml version="1.0"?>
<robot name="hostile">
  <link name="base">{_MASS.replace("0.1", "0")}
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    <visual><geometry><mesh filename={quoteattr("meshes/" + MESH)}/></geometry></visual>
  </link>
  <link name={picture}>{_MASS}
    <visual><origin xyz="0 0 0.1"/>{box}</visual>
    <collision><origin xyz="0 0 0.1"/>{box}</collision>
  </link>
  <link name={pipes}>{_MASS}
    <visual><origin xyz="0 0 0.1"/>{box}</visual>
    <collision><origin xyz="0 0 0.1"/>{box}</collision>
  </link>
  <joint name={tag} type="revolute">
    <parent link="base"/><child link={picture}/>
    <origin xyz="0,0,0.05"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <joint name={code} type="revolute">
    <parent link={picture}/><child link={pipes}/><origin xyz="0 0 0.2"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"""


def hostile_robot(folder: Path, page: bool = True) -> Path:
    """The robot's description and manifest in ``folder`` (output folder ``mjcf``); its
    manifest."""
    (folder / "meshes").mkdir(parents=True)
    ascii_stl(folder / "meshes" / MESH)
    (folder / "robot.urdf").write_text(hostile_urdf())
    manifest = folder / "robot.yaml"
    output = "output:\n  folder: mjcf\n" + ("  page: true\n" if page else "")
    manifest.write_text(f"name: hostile\nsource:\n  urdf: robot.urdf\n{output}")
    return manifest


def build(folder: Path) -> Path:
    """Build the robot in ``folder``; its output folder."""
    result = run_cli("build", cwd=folder)
    assert result.code == 0, result.stderr
    return folder / "mjcf"


# A code span: a run of backticks, then anything up to a run of the same length.
_CODE_SPAN = re.compile(r"(?<![`\\])(`+)(?!`)(.+?)(?<!`)\1(?!`)")
# CommonMark: a backslash before ASCII punctuation makes it a plain character.
_ESCAPED = re.compile(r"\\([!-/:-@\[-`{-~])")


def unescaped(text: str) -> str:
    """Markdown text with its backslash escapes read."""
    return _ESCAPED.sub(r"\1", text)


def bare(text: str, char: str) -> list[int]:
    """Where ``char`` stands in ``text`` without a backslash escaping it (an even number of
    backslashes before it)."""
    found = []
    for index, here in enumerate(text):
        if here == char:
            slashes = len(text[:index]) - len(text[:index].rstrip("\\"))
            if slashes % 2 == 0:
                found.append(index)
    return found


def cells(row: str) -> list[str]:
    """A pipe table row's cells, split where GitHub splits them: at each bare ``|``."""
    body = row.strip()
    cuts = [i for i in bare(body, "|") if 0 < i < len(body) - 1]
    bounds = [0, *cuts, len(body) - 1]
    return [unescaped(body[a + 1 : b].strip()) for a, b in itertools.pairwise(bounds)]


def tables(markdown: str) -> list[list[list[str]]]:
    """Every pipe table in ``markdown``: its rows' cells, the rule row left out."""
    found: list[list[list[str]]] = []
    previous = ""
    for line in markdown.splitlines():
        if line.startswith("|"):
            if not previous.startswith("|"):
                found.append([])
            if not set(line) <= set("|-: "):
                found[-1].append(cells(line))
        previous = line
    return found


def markup_outside_code(markdown: str) -> list[str]:
    """Lines of ``markdown`` (outside fenced code) with raw HTML or an autolink (a bare ``<``
    before a letter, ``/``, ``!`` or ``?``) or a link or picture (a bare ``[`` with ``](`` or
    ``][`` after it), other than the report's own pictures of its own files."""
    own = re.compile(r"^!\[[^\\\[\]]*\]\((previews|tuning)/[\w.%-]+\)$")
    found, fence = [], ""
    for line in markdown.splitlines():
        opening = re.match(r"^(`{3,})", line)
        if fence:
            if line.rstrip() == fence:  # a block ends at its own fence only
                fence = ""
            continue
        if opening:
            fence = opening.group(1)
            continue
        if own.match(line):
            continue
        line = _CODE_SPAN.sub("", line)
        tags = [i for i in bare(line, "<") if re.match(r"[A-Za-z/!?]", line[i + 1 : i + 2])]
        links = [i for i in bare(line, "[") if re.search(r"\]\(|\]\[", line[i:])]
        if tags or links:
            found.append(line)
    return found
