"""The self-collision matrix covers the geoms of ``attach:`` MJCF parts against the rest of the
model, and leaves pairs inside one part to the part."""

from __future__ import annotations

import json

import mjcfbuild
from tests.conftest import copy_example


def test_mjcf_part_geoms_are_in_the_matrix_and_their_resting_contacts_excluded(tmp_path):
    # The hand mounted on the arm's base, its palm and fingers inside the upper arm at home:
    # without the matrix covering the part, the check fails on three touching pairs (exit 6).
    folder = copy_example("arm_mjcf_gripper", tmp_path)
    manifest = folder / "robot.yaml"
    text = manifest.read_text().replace("to: tool0", "to: base_link")
    manifest.write_text(text.replace("pos: [0, 0, 0.06]", "pos: [0, 0, 0.2]"))
    result = mjcfbuild.build(manifest, jobs=1)
    assert result.ok, result
    matrix = json.loads((folder / "mjcf" / ".mjcfbuild" / "self_collision.json").read_text())
    verdicts = {(p["body1"], p["body2"]): p["reason"] for p in matrix["pairs"]}
    for body in ("hand_palm", "hand_left_finger", "hand_right_finger"):
        assert verdicts[("upper_arm_link", body)] == "home"
        assert ["upper_arm_link", body] in matrix["excludes"]
    # Pairs inside the hand are its own business: not in the matrix, never excluded.
    hand = {"hand_palm", "hand_left_finger", "hand_right_finger"}
    assert not [pair for pair in verdicts if set(pair) <= hand]
    check = json.loads((folder / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    assert check["passes"] and check["resting_contacts"]["pairs"] == []
    model = (folder / "mjcf" / "arm_with_mjcf_hand.xml").read_text()
    assert '<exclude body1="upper_arm_link" body2="hand_palm"/>' in model
    # Editing the hand reruns the matrix (its geoms are an input of it).
    hand_xml = folder / "hand" / "hand.xml"
    hand_xml.write_text(hand_xml.read_text().replace('size="0.035 0.005"', 'size="0.036 0.005"'))
    assert "selfcollision" in mjcfbuild.build(manifest, jobs=1, check=False).ran
