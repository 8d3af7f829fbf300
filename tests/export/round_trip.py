"""URDF -> MJCF -> URDF: the exported URDF puts every link of the original where the original
does at 20 random configurations, keeps its masses and its speed limits. Both URDFs'
kinematics are computed by mjcfbuild's own URDF forward kinematics, which shares no code with
MuJoCo. Used by tests/export/test_round_trip.py (unfused builds) and
tests/robots/test_real_robots.py (the fused builds those tests make anyway)."""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import pytest

from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.parse import parse_urdf
from mjcfbuild.urdf.transforms import rotation_angle_between

EXPORT = "output:\n  urdf: exported.urdf\n"  # robot.yaml lines that export the URDF


def random_configuration(robot, rng: random.Random) -> dict[str, float]:
    values = {}
    for joint in robot.joints:
        if joint.kind == "continuous":
            values[joint.name] = rng.uniform(-math.pi, math.pi)
        elif joint.kind in ("revolute", "prismatic"):
            limit = joint.limit
            low = limit.lower if limit and limit.lower is not None else -1.0
            high = limit.upper if limit and limit.upper is not None else 1.0
            values[joint.name] = rng.uniform(low, high)
    return values


def welded_to_world(robot) -> set[str]:
    """Links joined to a root link named 'world' by fixed joints only."""
    if robot.root != "world":
        return set()
    welded, children = {"world"}, robot.child_joints()
    pending = ["world"]
    while pending:
        for joint in children[pending.pop()]:
            if joint.kind == "fixed":
                welded.add(joint.child)
                pending.append(joint.child)
    return welded


def assert_round_trip(urdf: Path, robot_xml: Path, fuse_static: bool) -> None:
    """The URDF exported beside ``robot_xml`` (``output.urdf: exported.urdf``) round-trips
    the original ``urdf``."""
    exported_path = robot_xml.parent / "exported.urdf"
    report_path = robot_xml.parent / "report" / "report.json"
    original = parse_urdf(urdf.read_bytes(), str(urdf))
    exported = parse_urdf(exported_path.read_bytes(), str(exported_path))

    rng = random.Random(0)
    for _ in range(20):
        values = random_configuration(original, rng)
        assert set(values) <= {j.name for j in exported.joints}
        expected, actual = link_poses(original, values), link_poses(exported, values)
        # Poses relative to the original's root, which the export may have put under 'world'.
        actual_root = actual[original.root].inverse()
        for link in original.links:
            pose = actual_root.compose(actual[link.name])
            reference = expected[link.name]
            gap = max(abs(a - b) for a, b in zip(pose.position, reference.position, strict=True))
            assert gap < 1e-6, (link.name, gap)
            assert rotation_angle_between(pose.rotation, reference.rotation) < 1e-6, link.name

    # Every speed limit the original gives survives (from the servo's torque-speed line, or
    # from the URDF itself where the servo has none).
    speeds = {j.name: j.limit.velocity for j in exported.joints if j.limit is not None}
    for joint in original.joints:
        velocity = joint.limit.velocity if joint.limit is not None else None
        if joint.kind != "fixed" and velocity and velocity > 0 and joint.name in speeds:
            assert speeds[joint.name] == pytest.approx(velocity, rel=1e-9), joint.name

    report = json.loads(report_path.read_text())
    repaired = {repair["body"] for repair in report["repairs"]}
    masses = {link.name: (link.inertial.mass if link.inertial else 0.0) for link in original.links}
    exported_masses = {
        link.name: (link.inertial.mass if link.inertial else 0.0) for link in exported.links
    }
    if fuse_static:
        # Fused links' masses are in the body they were fused into, except links welded to a
        # root named 'world': they become part of MuJoCo's world body, which has no mass.
        welded = welded_to_world(original)
        kept = sum(m for n, m in exported_masses.items() if n not in repaired)
        expected_total = sum(m for n, m in masses.items() if n not in repaired | welded)
        assert kept == pytest.approx(expected_total)
    else:
        for link, mass in masses.items():
            if link not in repaired:
                assert exported_masses[link] == pytest.approx(mass, rel=1e-9, abs=1e-12), link
