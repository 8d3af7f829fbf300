"""Changes between two compiled models, found in the right group with the right values."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mjcfbuild.diff.compare import compare
from mjcfbuild.diff.snapshot import model_snapshot

MODEL = """<mujoco model="m">
  <compiler angle="radian"/>
  <worldbody>
    <body name="base" pos="0 0 0.1">
      <joint name="root" type="free"/>
      <geom type="box" size="0.1 0.1 0.05" mass="2"/>
      <body name="arm" pos="{arm_pos}" quat="{arm_quat}">
        <joint name="hinge" axis="0 1 0" range="{range}" damping="{damping}"/>
        <geom type="capsule" size="0.02 0.1" mass="0.5"/>
        <site name="tip" pos="0 0 0.2"/>
      </body>
    </body>
  </worldbody>
  <contact><exclude body1="base" body2="arm"/></contact>
  <actuator><position name="hinge" joint="hinge" kp="{kp}" kv="1"/></actuator>
  <keyframe><key name="home" qpos="0 0 0.1 1 0 0 0 {home}" ctrl="{home}"/></keyframe>
</mujoco>
"""

DEFAULTS = {
    "arm_pos": "0 0 0.1",
    "arm_quat": "1 0 0 0",
    "range": "-1 1",
    "damping": "0.5",
    "kp": "100",
    "home": "0.3",
}


def snapshot(folder: Path, name: str, **changes: str) -> dict:
    """The snapshot of :data:`MODEL` with ``changes`` to its fields."""
    path = folder / f"{name}.xml"
    path.write_text(MODEL.format(**{**DEFAULTS, **changes}))
    return model_snapshot(path)


def groups(before: dict, after: dict) -> dict:
    return compare(before, after).to_dict()


def test_the_same_model_compiled_twice_has_no_changes(tmp_path):
    diff = compare(snapshot(tmp_path, "a"), snapshot(tmp_path, "b"))
    assert diff.empty and diff.to_dict() == {}


def test_a_moved_link_says_how_far_relative_to_its_parent(tmp_path):
    found = groups(snapshot(tmp_path, "a"), snapshot(tmp_path, "b", arm_pos="0 0.003 0.1"))
    (change,) = found["kinematics"]
    assert change["subject"] == "body arm"
    assert change["after"]["pos"] == [0.0, 0.003, 0.1]
    assert "moved 0.003 m relative to base" in change["note"]


def test_a_turn_as_small_as_a_microradian_is_seen_and_rounding_is_not(tmp_path):
    angle = 1e-6
    quat = f"{math.cos(angle / 2):.17g} {math.sin(angle / 2):.17g} 0 0"
    (change,) = groups(snapshot(tmp_path, "a"), snapshot(tmp_path, "b", arm_quat=quat))[
        "kinematics"
    ]
    assert "turned 5.72958e-05 deg" in change["note"]
    # the same quarter turn twice: identical quaternions whose dot product rounds below 1 are
    # not 'turned' by 2e-6 degrees
    quarter = "0.707106781187 0 0 0.707106781187"
    assert compare(
        snapshot(tmp_path, "c", arm_quat=quarter), snapshot(tmp_path, "d", arm_quat=quarter)
    ).empty


def test_limits_gains_and_home_in_their_groups(tmp_path):
    found = groups(
        snapshot(tmp_path, "a"),
        snapshot(tmp_path, "b", range="-0.5 1", damping="2", kp="250", home="0.4"),
    )
    joints = {(c["subject"], c["what"]): (c["before"], c["after"]) for c in found["joints"]}
    assert joints == {
        ("joint hinge", "range"): ([-1.0, 1.0], [-0.5, 1.0]),
        ("joint hinge", "damping"): (0.5, 2.0),
    }
    (kp,) = found["actuators"]
    assert (kp["what"], kp["before"], kp["after"]) == ("kp", 100.0, 250.0)
    home = {(c["subject"], c["what"]): (c["before"], c["after"]) for c in found["home"]}
    assert home == {("joint hinge", "qpos"): (0.3, 0.4), ("actuator hinge", "ctrl"): (0.3, 0.4)}


def test_an_exclude_removed_is_in_the_collision_matrix(tmp_path):
    before = snapshot(tmp_path, "a")
    path = tmp_path / "b.xml"
    path.write_text(
        MODEL.format(**DEFAULTS).replace(
            '<contact><exclude body1="base" body2="arm"/></contact>', ""
        )
    )
    (change,) = groups(before, model_snapshot(path))["matrix"]
    assert change == {
        "subject": "arm / base",
        "what": "contact",
        "before": "excluded",
        "after": "collide",
        "note": "",
    }


def checks(verdict: str, failures: list[str], passes: bool) -> dict:
    return {
        "passes": passes,
        "failures": failures,
        "stand": {"verdict": verdict, "max_tilt": 1.2 if verdict == "falls" else 0.01},
        "hold_deviation": 0.01,
        "menagerie_finite": True,
        "menagerie_warnings": 0,
    }


def test_a_robot_that_stood_and_now_falls(tmp_path):
    before, after = snapshot(tmp_path, "a"), snapshot(tmp_path, "b")
    before["checks"] = checks("stands", [], True)
    fell = "the robot does not stand at home: ..."
    after["checks"] = checks("falls", [fell], False)
    found = {(c["subject"], c["what"]): c for c in groups(before, after)["checks"]}
    stand = found[("stand test", "robot")]
    assert (stand["before"], stand["after"]) == ("stands", "falls")
    assert "tilted 1.2 rad" in stand["note"]
    assert found[("check", "result")]["after"] == "failed"
    assert found[("check", "new failure")]["after"] == fell


@pytest.mark.parametrize("picture", ["front_visual.png"])
def test_a_changed_picture_is_named(tmp_path, picture):
    before, after = snapshot(tmp_path, "a"), snapshot(tmp_path, "b")
    before["previews"] = {picture: "1", "side_visual.png": "2"}
    after["previews"] = {picture: "3", "top_visual.png": "4"}
    found = {c["subject"]: c["what"] for c in groups(before, after)["previews"]}
    assert found == {picture: "changed", "side_visual.png": "removed", "top_visual.png": "added"}
