"""Errors about an expanded URDF's lines, pointed where their elements were written."""

from __future__ import annotations

from mjcfbuild.errors import InputError
from mjcfbuild.sources.origins import origins_file, point_at_source, write_origins, written_at


def test_an_error_inside_an_element_moves_to_where_the_element_was_written(tmp_path):
    urdf = tmp_path / "mjcf" / ".mjcfbuild" / "source.urdf"
    urdf.parent.mkdir(parents=True)
    urdf.write_text("<robot>\n<link>\n<visual/>\n</link>\n</robot>\n")
    xacro = tmp_path / "urdf" / "arm.xacro"
    write_origins(origins_file(urdf), {1: (str(xacro), 3), 2: (str(xacro), 10)}, {})
    assert origins_file(urdf).name == "source.origins.json"
    assert written_at(urdf, 3) == (str(xacro), 10)  # line 3 has no element of its own
    error = InputError(
        "bad mesh",
        file="mjcf/.mjcfbuild/source.urdf",
        line=3,
        hint="the line is in the expansion of x",
    )
    point_at_source(error, urdf, "mjcf/.mjcfbuild/source.urdf", tmp_path)
    assert (error.location.file, error.location.line) == ("urdf/arm.xacro", 10)
    assert error.message.startswith("bad mesh [expanded: ") and error.message.endswith(
        "source.urdf:3]"
    )
    assert error.hint is None
    other = InputError("elsewhere", file="robot.urdf", line=3)
    point_at_source(other, urdf, "mjcf/.mjcfbuild/source.urdf", tmp_path)
    assert (other.location.file, other.message) == ("robot.urdf", "elsewhere")
