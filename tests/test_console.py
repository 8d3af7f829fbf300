"""Error and warning lines as every front end prints them (mjcfbuild/console.py)."""

from __future__ import annotations

from mjcfbuild.console import report_error, report_warnings
from mjcfbuild.errors import InputError, InternalError


def test_an_error_is_one_line_on_stderr_with_its_place_and_hint(capsys):
    report_error(InputError("no such link 'arm'", file="robot.urdf", line=7, hint="fix it"), False)
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == "mjcfbuild: error: robot.urdf:7: no such link 'arm' (fix it)\n"


def test_an_internal_error_asks_for_debug_and_shows_its_traceback_with_it(capsys):
    error = InternalError("KeyError: 'x'", details="Traceback (most recent call last):\n  ...\n")
    report_error(error, debug=False)
    assert capsys.readouterr().err == (
        "mjcfbuild: error: KeyError: 'x' (an internal error: run again with --debug and report "
        "the output)\n"
    )
    report_error(error, debug=True)
    assert capsys.readouterr().err == (
        "mjcfbuild: error: KeyError: 'x'\nTraceback (most recent call last):\n  ...\n"
    )


def test_warnings_print_one_line_per_kind_after_the_prefix(capsys):
    boxes = [f"robot.urdf:{n}: link 'pad{n}' has a box of size 0" for n in (3, 5, 9, 12)]
    report_warnings([*boxes, "joint 'a' has no limit"], "report.md", prefix="arm: ")
    lines = capsys.readouterr().err.splitlines()
    assert lines == [
        "mjcfbuild: warning: arm: robot.urdf:3: 4 × link '…' has a box of size 0: pad3, pad5, "
        "pad9, ... 1 more (all in report.md)",
        "mjcfbuild: warning: arm: joint 'a' has no limit",
    ]


def test_a_warnings_files_are_named_from_where_the_command_runs(tmp_path, monkeypatch, capsys):
    """Kept warnings name files from robot.yaml's folder (the report, the no-op fast path):
    the console names both the file and the expanded URDF's line from here."""
    robot = tmp_path / "robots" / "arm"
    (robot / "mjcf" / ".mjcfbuild").mkdir(parents=True)
    (robot / "arm.urdf.xacro").write_text("<robot/>")
    (robot / "mjcf" / ".mjcfbuild" / "source.urdf").write_text("<robot/>")
    warning = "arm.urdf.xacro:7: a box of size 0 [expanded: mjcf/.mjcfbuild/source.urdf:28]"
    monkeypatch.chdir(tmp_path)
    report_warnings([warning], base_dir=robot)
    assert capsys.readouterr().err == (
        "mjcfbuild: warning: robots/arm/arm.urdf.xacro:7: a box of size 0 [expanded: "
        "robots/arm/mjcf/.mjcfbuild/source.urdf:28]\n"
    )
