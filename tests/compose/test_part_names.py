"""The names an MJCF part's unnamed joints take in the model."""

from __future__ import annotations

from mjcfbuild.compose.part_names import joint_names


def test_an_unnamed_joint_takes_its_bodys_name_and_never_one_taken():
    joints = [("", "thumb"), ("", "thumb"), ("thumb_joint3", "palm"), ("", "thumb"), ("", "")]
    assert joint_names(joints) == [
        "thumb_joint",
        "thumb_joint2",
        "thumb_joint3",
        "thumb_joint4",
        "",  # a joint of an unnamed body keeps no name
    ]
    assert joint_names([("hinge", "arm")]) == ["hinge"]
