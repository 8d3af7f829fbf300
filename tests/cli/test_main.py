"""The command line as a whole (mjcfbuild/cli/__init__.py): flags every command takes, before
or after its name, and what --debug shows."""

from __future__ import annotations

from mjcfbuild.errors import EXIT_MANIFEST, EXIT_OK
from tests.conftest import run_cli


def test_global_flags_go_before_or_after_the_command(arm):
    for argv in (["-q", "build", "--no-check"], ["build", "--no-check", "-q"]):
        result = run_cli(*argv, cwd=arm)
        assert result.code == EXIT_OK, result.stderr
        assert result.stdout == ""
    for argv in (["--debug", "graph"], ["graph", "--debug"], ["explain", "--debug", "-q"]):
        assert run_cli(*argv, cwd=arm).code == EXIT_OK, argv


def test_debug_prints_the_traceback_of_a_user_error_before_or_after_the_command(tmp_path):
    (tmp_path / "robot.yaml").write_text("name: r\nsource: {urdf: r.urdf}\nbogus: 1\n")
    plain = run_cli("build", cwd=tmp_path)
    assert plain.code == EXIT_MANIFEST and "Traceback" not in plain.stderr
    for argv in (["--debug", "build"], ["build", "--debug"], ["explain", "--debug"]):
        result = run_cli(*argv, cwd=tmp_path)
        assert result.code == EXIT_MANIFEST, result.stderr
        lines = result.stderr.splitlines()
        assert lines[0].startswith("mjcfbuild: error: robot.yaml:3:1:"), result.stderr
        assert "Traceback (most recent call last):" in lines


def test_debug_brings_the_traceback_of_an_error_raised_in_a_worker(tmp_path):
    (tmp_path / "robot.yaml").write_text("name: r\nsource: {urdf: r.urdf}\n")
    (tmp_path / "r.urdf").write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="gone.stl"/>'
        "</geometry></visual></link></robot>"
    )
    result = run_cli("build", "--debug", cwd=tmp_path)
    assert result.code == 4, result.stderr
    assert "gone.stl" in result.stderr and "Traceback" in result.stderr
