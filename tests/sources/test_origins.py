"""Errors about an expanded URDF's lines, pointed where their elements were written."""

from __future__ import annotations

from mjcfbuild.errors import InputError
from mjcfbuild.sources.origins import (
    map_lines,
    origins_file,
    origins_json,
    point_at_source,
    point_warning_at_source,
    source_location,
    written_at,
)


def test_an_error_inside_an_element_moves_to_where_the_element_was_written(tmp_path):
    urdf = tmp_path / "mjcf" / ".mjcfbuild" / "source.urdf"
    urdf.parent.mkdir(parents=True)
    urdf.write_text("<robot>\n<link>\n<visual/>\n</link>\n</robot>\n")
    xacro = tmp_path / "urdf" / "arm.xacro"
    origins_file(urdf).write_bytes(origins_json({1: (str(xacro), 3), 2: (str(xacro), 10)}))
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


def test_a_warning_about_an_expanded_line_names_the_written_one(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    urdf = tmp_path / "mjcf" / ".mjcfbuild" / "source.urdf"
    urdf.parent.mkdir(parents=True)
    origins_file(urdf).write_bytes(origins_json({5: (str(tmp_path / "urdf" / "arm.xacro"), 12)}))
    label = "mjcf/.mjcfbuild/source.urdf"
    warning = f'{label}:5: <origin rpy="1, 0, 0"> uses commas between numbers; read them as spaces'
    assert point_warning_at_source(warning, urdf, label, tmp_path) == (
        'urdf/arm.xacro:12: <origin rpy="1, 0, 0"> uses commas between numbers; read them as '
        "spaces [expanded: mjcf/.mjcfbuild/source.urdf:5]"
    )
    assert (
        point_warning_at_source("robot.yaml: other", urdf, label, tmp_path) == "robot.yaml: other"
    )


def test_an_error_about_the_whole_expanded_urdf_names_the_xacro_it_came_from(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    urdf = tmp_path / "mjcf" / ".mjcfbuild" / "source.urdf"
    urdf.parent.mkdir(parents=True)
    urdf.write_text("<robot/>\n")
    label = "mjcf/.mjcfbuild/source.urdf"
    xacro = tmp_path / "urdf" / "arm.urdf.xacro"
    error = InputError("no link of the robot has a mass", file=label)
    point_at_source(error, urdf, label, tmp_path, xacro)
    assert (error.location.file, error.location.line) == ("urdf/arm.urdf.xacro", None)
    assert error.message.endswith(" [expanded: mjcf/.mjcfbuild/source.urdf]")
    # Without the xacro (an attached part's URDF), the error keeps the file it names.
    kept = InputError("no link of the robot has a mass", file=label)
    point_at_source(kept, urdf, label, tmp_path)
    assert (kept.location.file, kept.message) == (label, "no link of the robot has a mass")


def test_the_first_line_of_a_name_given_twice_is_mapped_with_the_error(tmp_path):
    # it was left an expanded line: "xacro:13: ... (first at line 13)", the first at xacro:8
    origins = {8: ("arm.xacro", 8), 13: ("arm.xacro", 8), 23: ("arm.xacro", 13)}
    error = InputError(
        "link 'plate' is defined twice (first at line 13)",
        file="source.urdf",
        line=23,
        first_line=13,
    )
    assert map_lines(error, origins) == 23
    assert str(error.location) == "arm.xacro:13"
    assert error.message == "link 'plate' is defined twice (first at line 8)"
    other = InputError("x is defined twice (first at line 13)", file="s", line=23, first_line=13)
    map_lines(other, {13: ("macros.xacro", 4), 23: ("arm.xacro", 13)})
    assert other.message == "x is defined twice (first at macros.xacro:4)"
    sent = InputError.from_dict(InputError("m", file="f", line=2, first_line=1).to_dict())
    assert sent.first_line == 1


def test_a_warnings_source_outside_the_manifest_folder_is_named_from_it(tmp_path):
    """The report keeps placed warnings: a xacro in a sibling folder is named from robot.yaml's
    folder (the same text wherever both are copied), not by its absolute path."""
    base = tmp_path / "robot"
    urdf = base / "mjcf" / ".mjcfbuild" / "source.urdf"
    urdf.parent.mkdir(parents=True)
    xacro = tmp_path / "description" / "arm.urdf.xacro"
    origins_file(urdf).write_bytes(origins_json({5: (str(xacro), 12)}))
    label = "mjcf/.mjcfbuild/source.urdf"
    assert source_location(f"{label}:7", urdf, label, base) == "../description/arm.urdf.xacro:12"
    assert source_location(f"{label}:4", urdf, label, base) == f"{label}:4"  # before any
    assert source_location("robot.urdf:7", urdf, label, base) == "robot.urdf:7"
    assert point_warning_at_source(f"{label}:7: a warning", urdf, label, base) == (
        "../description/arm.urdf.xacro:12: a warning [expanded: mjcf/.mjcfbuild/source.urdf:7]"
    )
