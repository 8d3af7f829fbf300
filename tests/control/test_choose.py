"""Choosing actuators: the warnings about URDF limits that are not limits."""

from __future__ import annotations

from mjcfbuild.control.choose import limit_notes
from mjcfbuild.urdf.parse import parse_urdf
from tests.conftest import two_link_urdf


def test_zero_effort_and_velocity_each_say_what_gives_that_limit():
    # mani_skill's so100.urdf writes effort="0" velocity="0" on every joint
    urdf = two_link_urdf().replace('effort="10" velocity="1"', 'effort="0" velocity="0"')
    notes = limit_notes(parse_urdf(urdf.encode(), "r.urdf"))
    assert notes == [
        "r.urdf:11: joint 'hinge' has effort=\"0\": not a limit, taken as unknown (no effort "
        "limit); give the real one in the URDF or with a rule's forcerange",
        "r.urdf:11: joint 'hinge' has velocity=\"0\": not a limit, taken as unknown (no "
        "velocity limit); give the real one in the URDF or with a rule's motor (its "
        "no_load_speed)",
    ]


def test_a_limit_in_a_xacro_source_is_named_at_the_xacro_line(tmp_path):
    """The console places the warning at the joint in the xacro file (it named the expanded
    URDF's line)."""
    import shutil

    from tests.conftest import EXAMPLES, run_cli

    arm = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    xacro = arm / "urdf" / "arm.urdf.xacro"
    lines = xacro.read_text().splitlines(keepends=True)
    xacro.write_text("".join(lines).replace('<limit effort="10"', '<limit effort="0"', 1))
    number = next(i for i, line in enumerate(lines, 1) if '<joint name="wrist_roll"' in line)
    result = run_cli("build", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    assert (
        f"mjcfbuild: warning: urdf/arm.urdf.xacro:{number}: joint 'wrist_roll' has "
        'effort="0": not a limit'
    ) in result.stderr, result.stderr
