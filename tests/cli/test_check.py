"""``mjcfbuild check`` refuses options that cannot go together, and prints failures of one
kind on one line (its other tests are in tests/check/test_check_command.py)."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import EXIT_INPUT, EXIT_USAGE
from tests.conftest import run_cli, simple_manifest, two_link_urdf, write

PAIR = ["--urdf", "robot.urdf", "--mjcf", "model.xml"]


@pytest.mark.parametrize(
    ("argv", "refused"),
    [
        (["robot.yaml", *PAIR], "a manifest (robot.yaml) and --urdf/--mjcf"),
        (["-m", "robot.yaml", *PAIR], "a manifest (robot.yaml) and --urdf/--mjcf"),
        (["--up-to-date", *PAIR], "--up-to-date and --urdf/--mjcf"),
        (["--warp", "--urdf", "robot.urdf"], "--warp and --urdf"),
    ],
)
def test_a_manifest_or_its_options_beside_urdf_and_mjcf_are_refused(argv, refused, tmp_path):
    # Files that are there: each combination checked the pair and ignored the rest.
    write(tmp_path / "robot.urdf", two_link_urdf())
    simple_manifest(tmp_path)
    write(tmp_path / "model.xml", "<mujoco/>\n")
    result = run_cli("check", *argv, cwd=tmp_path)
    assert result.code == EXIT_USAGE
    assert result.stderr.startswith(f"mjcfbuild: error: {refused} cannot go together (")
    assert result.stderr.count("\n") == 1 and result.stdout == ""


def test_failures_of_one_kind_are_one_line_with_where_they_all_are(capsys):
    from mjcfbuild.check.results import CheckResults
    from mjcfbuild.cli.check import _print
    from mjcfbuild.errors import EXIT_CHECK

    fast = [
        f"joint '{name}' reached {speed} rad/s under pseudorandom control, more than 50 times "
        "its velocity limit 3 rad/s (urdf)"
        for name, speed in (("a", 400), ("b", 500), ("c", 600), ("d", 700))
    ]
    results = CheckResults(loads=True, failures=["the state is not finite", *fast])
    assert _print(results, "model.xml", listed_in="report.md") == EXIT_CHECK
    failed = capsys.readouterr().err.splitlines()
    assert failed == [
        "mjcfbuild: check failed: the state is not finite",
        f"mjcfbuild: check failed: {fast[0]} (and 3 more like it: b, c, d)",
    ]
    # Three of a kind are shown each with its figures.
    results = CheckResults(loads=True, failures=fast[:3])
    _print(results, "model.xml", listed_in="report.md")
    assert capsys.readouterr().err.splitlines() == [
        f"mjcfbuild: check failed: {failure}" for failure in fast[:3]
    ]


def test_a_urdf_given_for_the_mjcf_is_refused_for_what_it_is(tmp_path):
    """MuJoCo reads a URDF in an MJCF's place: the check would compare the URDF with itself."""
    write(tmp_path / "robot.urdf", two_link_urdf())
    result = run_cli("check", "--urdf", "robot.urdf", "--mjcf", "robot.urdf", cwd=tmp_path)
    assert result.code == EXIT_INPUT
    assert result.stderr.startswith(
        "mjcfbuild: error: robot.urdf: this is a URDF, not an MJCF model (--mjcf takes the "
    )
