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
        "joint 'hinge' has effort=\"0\" in the URDF (line 11): not a limit, taken as unknown "
        "(no effort limit); give the real one in the URDF or with a rule's forcerange",
        "joint 'hinge' has velocity=\"0\" in the URDF (line 11): not a limit, taken as unknown "
        "(no velocity limit); give the real one in the URDF or with a rule's motor (its "
        "no_load_speed)",
    ]
