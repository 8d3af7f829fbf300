"""A torque-speed line's rotor that no real drive of the joint could have is warned about."""

from __future__ import annotations

import mujoco
import pytest

import mjcfbuild
from tests.conftest import write

PHALANX = 0.0004  # kg: a 3.1 g hand (a 1.5 g palm, two fingers of two phalanges)


def _hand_urdf(effort: float = 1000, velocity: float = 1, masses: bool = True) -> str:
    """A 3.1 g two-finger hand on a fixed palm, every joint with ``effort`` and ``velocity``;
    without ``masses``, the distal phalanges have no <inertial>."""
    tensor = 'ixx="1.4e-08" iyy="1.4e-08" izz="1e-08" ixy="0" ixz="0" iyz="0"'
    parts = [
        '<robot name="tiny_hand">',
        '<link name="palm"><inertial><mass value="0.0015"/><inertia ixx="1e-07" iyy="1e-07" '
        'izz="1e-07" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><box '
        'size="0.03 0.01 0.03"/></geometry></collision></link>',
    ]
    for finger, x in (("index", 0.01), ("thumb", -0.01)):
        parent = "palm"
        for k, z in ((1, 0.015), (2, 0.02)):
            link = f"{finger}_{k}"
            inertial = (
                f'<inertial><origin xyz="0 0 0.01"/><mass value="{PHALANX}"/><inertia {tensor}/>'
                "</inertial>"
                if masses or k == 1
                else ""
            )
            parts += [
                f'<link name="{link}">{inertial}<collision><origin xyz="0 0 0.01"/><geometry>'
                '<cylinder radius="0.003" length="0.02"/></geometry></collision></link>',
                f'<joint name="{link}_joint" type="revolute"><parent link="{parent}"/>'
                f'<child link="{link}"/><origin xyz="{x if k == 1 else 0} 0 {z}"/>'
                f'<axis xyz="1 0 0"/><limit lower="0" upper="1.5" effort="{effort}" '
                f'velocity="{velocity}"/></joint>',
            ]
            parent = link
    return "\n".join([*parts, "</robot>", ""])


def _build(folder, urdf: str, manifest: str = ""):
    write(folder / "hand.urdf", urdf)
    write(folder / "robot.yaml", "name: tiny_hand\nsource: {urdf: hand.urdf}\n" + manifest)
    result = mjcfbuild.build(folder / "robot.yaml", check=False)
    assert not result.errors, result.errors
    return result


def _rotor_warnings(result) -> list[str]:
    return [w for w in result.warnings if "give it a rotor inertia (armature)" in w]


def test_placeholder_limits_on_a_tiny_hand_are_warned_about_joint_by_joint(tmp_path):
    # 1000 N m and 1 rad/s gave each joint of a 3.1 g hand 2 kg m^2 of armature, silently.
    urdf = _hand_urdf()
    result = _build(tmp_path, urdf)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert list(model.dof_armature) == pytest.approx([2.0] * 4)  # the line stays as it was
    found = _rotor_warnings(result)
    assert len(found) == 4, result.warnings
    line = next(n for n, text in enumerate(urdf.splitlines(), 1) if 'name="index_2_joint"' in text)
    distal = next(w for w in found if "'index_2_joint'" in w)
    assert distal.startswith(
        f"hand.urdf:{line}: joint 'index_2_joint': its URDF limits (effort 1000 N m, velocity "
        "1 rad/s) give it a rotor inertia (armature) of 2 kg m^2, "
    )
    # The distal phalanx: 0.4 g whose cylinder reaches 0.02 m plus its bounding radius.
    assert f"times the most its {PHALANX:g} kg of links at up to 0.0204 m" in distal
    assert distal.endswith(
        "the limits (or the links' masses) look like placeholders; give the joint its real "
        "effort and velocity in the URDF, or its real effort E in robot.yaml: actuators: "
        "{rules: [{joints: "
        '["index_2_joint"], forcerange: [-E, E]}]}'
    )


def test_the_forcerange_the_warning_names_ends_it(tmp_path):
    rule = 'actuators: {rules: [{joints: ["*"], forcerange: [-0.01, 0.01]}]}\n'
    result = _build(tmp_path, _hand_urdf(), rule)
    assert _rotor_warnings(result) == []
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert list(model.dof_armature) == pytest.approx([2e-5] * 4)


def test_an_effort_from_a_rule_is_blamed_on_the_rule_at_its_line(tmp_path):
    # The URDF's effort is 1 N m; a rule's forcerange gave the line its 500 N m, and the
    # warning said "its URDF limits (effort 500 N m, ...)" and sent the user to the URDF.
    shared = 'actuators: {rules: [{joints: ["*"], forcerange: [-500, 500]}]}\n'
    found = _rotor_warnings(_build(tmp_path / "shared", _hand_urdf(effort=1), shared))
    assert len(found) == 4, found
    warning = next(w for w in found if "'index_1_joint'" in w)
    assert "URDF limits" not in warning
    assert "its effort 500 N m (from robot.yaml:3: actuators.rules[0].forcerange) and URDF " in (
        warning
    )
    # The rule drives every joint: the fix is a rule of the joint's own, put before it.
    assert warning.endswith(
        "look like placeholders; give the joint its real effort E in a rule of its own before "
        'that one ({joints: ["index_1_joint"], forcerange: [-E, E]}: the first rule matching a '
        "joint applies), and its real velocity in the URDF"
    )
    own = "actuators:\n  rules:\n    - joints: [index_1_joint]\n      forcerange: [-500, 500]\n"
    found = _rotor_warnings(_build(tmp_path / "own", _hand_urdf(effort=1), own))
    # (1 N m at 1 rad/s still weighs down the other joints' phalanges: their own warnings)
    ruled = [w for w in found if "actuators.rules" in w]
    assert len(ruled) == 1 and "'index_1_joint'" in ruled[0], found
    assert "(from robot.yaml:6: actuators.rules[0].forcerange)" in ruled[0]
    assert ruled[0].endswith(
        "give the joint its real effort E in that rule (forcerange: [-E, E]), and its real "
        "velocity in the URDF"
    )


def test_plausible_limits_and_a_rules_armature_are_not_warned_about(tmp_path):
    # A micro servo's 0.1 N m at 5 rad/s: a rotor of 4e-5 kg m^2, 30 to 240 times what the
    # phalanges could have, as geared drives in fingers really are.
    assert _rotor_warnings(_build(tmp_path / "real", _hand_urdf(0.1, 5))) == []
    rule = 'actuators: {rules: [{joints: ["*"], armature: 0.5}]}\n'
    assert _rotor_warnings(_build(tmp_path / "rule", _hand_urdf(), rule)) == []


def test_links_without_mass_are_left_to_their_own_warning(tmp_path):
    # The 0.1 g placeholder a massless link gets says nothing of the drive's limits.
    assert _rotor_warnings(_build(tmp_path, _hand_urdf(masses=False))) == []
