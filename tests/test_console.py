"""Error and warning lines as every front end prints them (mjcfbuild/console.py)."""

from __future__ import annotations

import pytest

from mjcfbuild.console import report_error, report_warnings
from mjcfbuild.errors import InputError, InternalError, ManifestError
from tests.conftest import write


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


@pytest.mark.parametrize("out", ["mjcf", "my model"])
@pytest.mark.parametrize("source", ["arm.urdf.xacro", "my arm.urdf.xacro"])
def test_a_warnings_files_are_named_from_where_the_command_runs(
    tmp_path, monkeypatch, capsys, out, source
):
    """Kept warnings name files from robot.yaml's folder (the report, the no-op fast path):
    the console names both the file and the expanded URDF's line from here, spaces or not."""
    robot = tmp_path / "robots" / "arm"
    (robot / out / ".mjcfbuild").mkdir(parents=True)
    (robot / source).write_text("<robot/>")
    (robot / out / ".mjcfbuild" / "source.urdf").write_text("<robot/>")
    warning = f"{source}:7: a box of size 0 [expanded: {out}/.mjcfbuild/source.urdf:28]"
    monkeypatch.chdir(tmp_path)
    report_warnings([warning, "mass 0.5 kg: not a file"], base_dir=robot)
    assert capsys.readouterr().err == (
        f"mjcfbuild: warning: robots/arm/{source}:7: a box of size 0 [expanded: "
        f"robots/arm/{out}/.mjcfbuild/source.urdf:28]\n"
        "mjcfbuild: warning: mass 0.5 kg: not a file\n"
    )


def test_an_error_at_a_merge_conflicts_marker_says_so(tmp_path, monkeypatch, capsys):
    """A YAML file git left conflicted read as a plain syntax error ("could not find expected
    ':'"), the parser stopping on the marker or the line after it."""

    write(tmp_path / "limits.yaml", "a: 1\n<<<<<<< HEAD\nb: 2\n=======\nb: 3\n>>>>>>> other\n")
    monkeypatch.chdir(tmp_path)
    for line in (2, 3):
        report_error(ManifestError("YAML syntax error", file="limits.yaml", line=line), False)
        assert capsys.readouterr().err == (
            f"mjcfbuild: error: limits.yaml:{line}: YAML syntax error (git left a merge "
            "conflict's marker there: resolve the conflict, then build)\n"
        )
    report_error(ManifestError("bad", file="limits.yaml", line=1, hint="fix it"), False)
    assert capsys.readouterr().err == "mjcfbuild: error: limits.yaml:1: bad (fix it)\n"
    # A banner of '=' signs in a comment is no marker.
    write(tmp_path / "arm.xacro", "<!--\n======= joints =======\n-->\n<robot\n")
    report_error(ManifestError("XML error", file="arm.xacro", line=3, hint="fix it"), False)
    assert capsys.readouterr().err == "mjcfbuild: error: arm.xacro:3: XML error (fix it)\n"
