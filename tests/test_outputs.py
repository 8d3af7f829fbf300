"""Where a build's files lie (mjcfbuild/outputs.py), for the examples as they are."""

from __future__ import annotations

import shutil

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.outputs import (
    COMPOSED_URDF,
    SOURCE_URDF,
    mjcf_part_paths,
    part_urdf,
    planned_urdf,
    report_dir,
)
from tests.conftest import EXAMPLES


def _context(tmp_path, example: str) -> BuildContext:
    folder = tmp_path / example
    shutil.copytree(EXAMPLES / example, folder, ignore=shutil.ignore_patterns("mjcf"))
    return BuildContext.from_manifest_file(folder / "robot.yaml")


def test_the_plan_reads_the_composed_urdf_only_when_urdf_parts_are_attached(tmp_path):
    arm = _context(tmp_path, "arm")
    assert planned_urdf(arm) == arm.state_dir / SOURCE_URDF
    gripper = _context(tmp_path, "arm_gripper")  # a xacro gripper joined to the arm
    assert planned_urdf(gripper) == gripper.state_dir / COMPOSED_URDF
    hand = _context(tmp_path, "arm_mjcf_gripper")  # an MJCF hand: attached to the model
    assert planned_urdf(hand) == hand.state_dir / SOURCE_URDF


def test_every_file_lies_in_the_output_folder(tmp_path):
    _context(tmp_path, "arm")  # the hand's example reads the arm's description
    ctx = _context(tmp_path, "arm_mjcf_gripper")
    paths = [report_dir(ctx), part_urdf(ctx, 0), *mjcf_part_paths(ctx, 0).values()]
    assert all(path.is_relative_to(ctx.out_dir) for path in paths)
    assert len(set(mjcf_part_paths(ctx, 0).values()) | set(mjcf_part_paths(ctx, 1).values())) == 7
