"""Whether a base floats, from kinematics and geometry (mjcfbuild init's question)."""

from __future__ import annotations

from mjcfbuild.urdf.base import classify_base
from mjcfbuild.urdf.parse import parse_urdf
from tests.control import robots

BOX_TRUNK = '<collision><geometry><box size="0.45 0.25 0.1"/></geometry></collision>'


def hand(square: bool = False, phalanges: int = 3) -> str:
    """A palm at the top with four fingers of three phalanges hanging below it in a row, 2 cm
    apart, and a thumb to the side: the zero pose of the inspire and fourier hands. ``square``
    puts the fingers at the corners of a square instead, as a quadruped's legs stand; more
    ``phalanges`` make the same fingers of that many short links (a deep tree)."""
    inertial = robots.inertial
    parts = []
    for index in range(4):
        x = (index - 1.5) * 0.02
        y = 0.0
        if square:
            x, y = (0.04 if index % 2 else -0.04), (0.04 if index // 2 else -0.04)
        previous = "palm"
        lengths = (0.05, 0.035, 0.03) if phalanges == 3 else (0.115 / phalanges,) * phalanges
        for phalanx, length in enumerate(lengths):
            name = f"finger{index}_{phalanx}"
            origin = f"{x} {y} -0.1" if phalanx == 0 else f"0 0 {-lengths[phalanx - 1]}"
            parts.append(
                f"""<link name="{name}">{inertial(0.01, f"0 0 {-length / 2}")}
  <collision><origin xyz="0 0 {-length / 2}"/><geometry><cylinder radius="0.008" length="{length}"/></geometry></collision></link>
<joint name="{name}_joint" type="revolute"><parent link="{previous}"/><child link="{name}"/>
  <origin xyz="{origin}"/><axis xyz="1 0 0"/><limit lower="0" upper="1.5" effort="1" velocity="2"/></joint>"""
            )
            previous = name
    return f"""<robot name="hand">
<link name="palm">{inertial(0.3, "0 0 -0.05")}
  <collision><origin xyz="0 0 -0.05"/><geometry><box size="0.09 0.03 0.1"/></geometry></collision></link>
<link name="thumb">{inertial(0.02)}
  <collision><origin xyz="0.03 0 0"/><geometry><cylinder radius="0.01" length="0.04"/></geometry></collision></link>
<joint name="thumb_joint" type="revolute"><parent link="palm"/><child link="thumb"/>
  <origin xyz="0.05 0 -0.05"/><axis xyz="0 0 1"/><limit lower="0" upper="1.5" effort="1" velocity="2"/></joint>
{"".join(parts)}
</robot>"""


def test_a_hand_whose_fingers_hang_below_the_palm_is_fixed():
    kind = classify_base(parse_urdf(hand().encode(), "hand.urdf"))
    assert not kind.floating
    assert "hand's fingers" in kind.why


def test_fingers_hundreds_of_links_deep_are_walked_without_recursion():
    # The limbs that reach the floor and their lowest points, on chains 600 links long.
    kind = classify_base(parse_urdf(hand(phalanges=600).encode(), "hand.urdf"))
    assert not kind.floating and "hand's fingers" in kind.why, kind.why
    kind = classify_base(parse_urdf(hand(square=True, phalanges=600).encode(), "hand.urdf"))
    assert kind.floating and "4 limbs" in kind.why, kind.why


def test_legs_standing_apart_float_even_with_nothing_above_the_trunk():
    for urdf in (robots.quadruped(), robots.quadruped().replace(BOX_TRUNK, "")):
        kind = classify_base(parse_urdf(urdf.encode(), "quad.urdf"))
        assert kind.floating, kind.why
        assert "4 limbs" in kind.why


def test_the_same_chains_at_the_corners_of_a_square_are_legs():
    # The rule is the row the fingertips end in: the same chains standing apart span an area.
    kind = classify_base(parse_urdf(hand(square=True).encode(), "hand.urdf"))
    assert kind.floating, kind.why


def test_a_low_slung_base_on_large_wheels_floats():
    """Jackal's shape: the wheels' axles at half the robot's height, below every other moving
    joint (the lowest-quarter rule alone calls it fixed)."""
    inertial = robots.inertial
    wheels = "".join(
        f"""<link name="{side}_wheel">{inertial(0.5)}
  <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision></link>
<joint name="{side}_wheel_joint" type="continuous"><parent link="base"/><child link="{side}_wheel"/>
  <origin xyz="{x} {y} -0.05"/><axis xyz="0 1 0"/><limit effort="5" velocity="10"/></joint>"""
        for side, x, y in (
            ("fl", 0.15, 0.2),
            ("fr", 0.15, -0.2),
            ("rl", -0.15, 0.2),
            ("rr", -0.15, -0.2),
        )
    )
    urdf = f"""<robot name="rover"><link name="base">{inertial(10.0)}
  <collision><geometry><box size="0.4 0.3 0.12"/></geometry></collision></link>{wheels}</robot>"""
    kind = classify_base(parse_urdf(urdf.encode(), "rover.urdf"))
    assert kind.floating, kind.why
    assert "wheels" in kind.why


def test_a_robot_without_moving_joints_floats():
    """hector's quadrotor: one link (and here a fixed camera), no joints. Bolted down it could
    never move; free, thrust moves it."""
    inertial = robots.inertial
    urdf = f"""<robot name="quadrotor">
<link name="base">{inertial(1.5)}
  <collision><geometry><box size="0.5 0.5 0.1"/></geometry></collision></link>
<link name="camera">{inertial(0.05)}</link>
<joint name="camera_mount" type="fixed"><parent link="base"/><child link="camera"/>
  <origin xyz="0.2 0 -0.05"/></joint>
</robot>"""
    kind = classify_base(parse_urdf(urdf.encode(), "quadrotor.urdf"))
    assert kind.floating and "no moving joints" in kind.why
    # The same body with one joint that moves is judged by its shape: an arm's plate is fixed.
    arm = urdf.replace('type="fixed"', 'type="revolute"').replace(
        '<origin xyz="0.2 0 -0.05"/></joint>',
        '<origin xyz="0.2 0 0.05"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>',
    )
    assert not classify_base(parse_urdf(arm.encode(), "arm.urdf")).floating


def test_a_floating_joint_from_a_placeholder_root_floats():
    arm = (
        '<robot name="r"><link name="root"/><link name="trunk"/><joint name="f" '
        'type="floating"><parent link="root"/><child link="trunk"/></joint></robot>'
    )
    kind = classify_base(parse_urdf(arm.encode(), "r.urdf"))
    assert kind.floating and "floating joint" in kind.why
