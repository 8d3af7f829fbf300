"""The panda with example-robot-data's own SRDF: every <disable_collisions> pair is excluded
(mapped through fused links) and listed in the report with the SRDF's reason."""

from __future__ import annotations

import json

import pytest

import mjcfbuild
from bench import robot_data
from mjcfbuild.mjcf.bodies import build_bodies
from mjcfbuild.selfcollision.srdf import parse_srdf
from mjcfbuild.urdf.model import robot_from_dict

pytestmark = [pytest.mark.robots, pytest.mark.slow]


def test_every_srdf_pair_is_excluded_and_reported(tmp_path):
    robot = robot_data.ROBOTS["panda"]
    urdf = robot_data.unpack(robot)
    srdf = urdf.parent.parent / "srdf" / "panda.srdf"
    manifest = robot_data.manifest(
        robot,
        tmp_path,
        urdf,
        robot_data.package_root(),
        extra=f"self_collision: {{srdf: {srdf}, home_state: default}}\n",
    )
    result = mjcfbuild.build(manifest, jobs=2)  # the check passes, or this raises

    state = tmp_path / "mjcf" / ".mjcfbuild"
    assembly = json.loads((state / "assembly.json").read_text())
    plan_robot = robot_from_dict(json.loads((state / "plan.json").read_text())["robot"])
    body_of = {f.link: b.name for b in build_bodies(plan_robot, True) for f in b.links}
    pairs = {frozenset((p["body1"], p["body2"])): p for p in assembly["self_collision"]["pairs"]}
    colliding = {body for key in pairs for body in key}
    declared = parse_srdf(srdf.read_bytes(), str(srdf)).pairs
    assert len(declared) == 35
    excluded = 0
    for pair in declared:
        bodies = frozenset((body_of[pair.link1], body_of[pair.link2]))
        verdict = pairs.get(bodies)
        if verdict is None:  # fused into one body, or a body without collision geometry
            assert len(bodies) == 1 or not bodies <= colliding
            continue
        assert verdict["exclude"], verdict
        assert verdict["reason"].startswith("srdf: ") or verdict["reason"] == "adjacent"
        excluded += 1
    assert excluded >= 20
    report = (result.robot.parent / "report" / "report.md").read_text()
    assert "srdf: Never" in report or "srdf: Adjacent" in report
    # The SRDF's 'default' group state is the home pose.
    home = {h["joint"]: h for h in assembly["readiness"]["home"]}
    assert home["panda_joint4"]["value"] == pytest.approx(-2.35619)
    assert home["panda_joint4"]["source"] == "srdf"
