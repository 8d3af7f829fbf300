"""Bodies touching at rest: pairs between bodies of the model fail the check; pairs inside one
hand-tuned MJCF part are the part's business, reported but not failed."""

from __future__ import annotations

import json
import re

import mujoco

import mjcfbuild
from mjcfbuild.check.contacts import RestingContact, split_by_part
from tests.conftest import copy_example, run_cli


def closed_hand(tmp_path):
    """The example arm with its MJCF hand changed to close its fingers at qpos0, touching (2 mm
    deep), with no keyframe: as a MuJoCo Menagerie gripper comes."""
    folder = copy_example("arm_mjcf_gripper", tmp_path)
    hand = folder / "hand" / "hand.xml"
    text = hand.read_text().replace('pos="0 0.006 0.0225"', 'pos="0 0.005 0.0225"')
    text = re.sub(r"<keyframe>.*</keyframe>", "", text, flags=re.S)
    hand.write_text(text)
    return folder


def test_fingers_of_an_mjcf_part_touching_at_rest_pass_and_are_listed(tmp_path):
    folder = closed_hand(tmp_path)
    # The hand alone: its fingers do touch at qpos0.
    alone = mujoco.MjModel.from_xml_path(str(folder / "hand" / "hand.xml"))
    data = mujoco.MjData(alone)
    mujoco.mj_forward(alone, data)
    assert data.ncon > 0
    result = mjcfbuild.build(folder / "robot.yaml", jobs=1)
    assert result.ok, result
    check = json.loads((folder / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    assert check["passes"], check["failures"]
    contacts = check["resting_contacts"]
    assert contacts["pairs"] == []
    (pair,) = contacts["inside_parts"]
    assert {pair["body1"], pair["body2"]} == {"hand_left_finger", "hand_right_finger"}
    assert pair["part"] == "hand_ (hand/hand.xml)"
    page = (folder / "mjcf" / "report" / "report.md").read_text()
    assert "hand_left_finger and hand_right_finger in hand_ (hand/hand.xml)" in page
    # `mjcfbuild check` reads the build's parts the same way.
    done = run_cli("check", cwd=folder)
    assert done.code == 0, done.stdout + done.stderr
    check = json.loads((folder / "mjcf" / ".mjcfbuild" / "check.json").read_text())
    assert len(check["resting_contacts"]["inside_parts"]) == 1


def test_a_pair_across_a_part_and_the_model_is_not_the_parts_business():
    touching = [
        RestingContact("hand_left_finger", "hand_right_finger", 0.002, "home"),
        RestingContact("hand_palm", "wrist", 0.001, "home"),
    ]
    parts = {"hand_ (hand/hand.xml)": {"hand_palm", "hand_left_finger", "hand_right_finger"}}
    model_pairs, inside = split_by_part(touching, parts)
    assert [(c.body1, c.body2) for c in model_pairs] == [("hand_palm", "wrist")]
    assert [(part, c.body1) for part, c in inside] == [
        ("hand_ (hand/hand.xml)", "hand_left_finger")
    ]
