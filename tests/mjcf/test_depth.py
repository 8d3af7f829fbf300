"""How deep bodies may nest: MuJoCo's own limit, and chains refused at the joint past it."""

from __future__ import annotations

import mujoco
import pytest

from bench.deep_chain import snake_urdf
from mjcfbuild.errors import EXIT_MODEL, ModelError
from mjcfbuild.mjcf.bodies import build_bodies
from mjcfbuild.mjcf.depth import MAX_BODY_DEPTH, refuse_deep_bodies, refuse_deep_chains
from mjcfbuild.urdf.parse import parse_urdf


def nested_bodies(depth: int) -> str:
    """MJCF of ``depth`` bodies each inside the one before, each with a joint and a geom (as
    mjcfbuild writes them)."""
    body = '<body pos="0.05 0 0"><joint axis="0 0 1"/><geom type="box" size=".025 .01 .01"/>'
    return f"<mujoco><worldbody>{body * depth}{'</body>' * depth}</worldbody></mujoco>"


def test_mujoco_reads_as_many_nested_bodies_as_the_limit_and_no_more():
    # If MuJoCo's XML reader changes its limit, this says so and MAX_BODY_DEPTH must follow.
    assert mujoco.MjModel.from_xml_string(nested_bodies(MAX_BODY_DEPTH)).nbody == 497
    with pytest.raises(ValueError, match="nesting is too deep"):
        mujoco.MjModel.from_xml_string(nested_bodies(MAX_BODY_DEPTH + 1))
    with pytest.raises(ValueError, match="nesting is too deep"):
        mujoco.MjSpec.from_string(nested_bodies(MAX_BODY_DEPTH + 1))


def test_a_chain_past_the_limit_is_refused_at_the_joint_that_passes_it():
    text = snake_urdf(MAX_BODY_DEPTH + 2)
    robot = parse_urdf(text.encode(), "snake.urdf")
    with pytest.raises(ModelError) as caught:
        refuse_deep_chains(robot)
    error = caught.value
    assert error.exit_code == EXIT_MODEL
    assert error.location is not None and error.location.file == "snake.urdf"
    assert (
        error.location.line
        == text.splitlines().index(
            '  <joint name="j496" type="revolute"><parent link="l495"/><child link="l496"/>'
        )
        + 1
    )
    assert "nests bodies 498 deep and MuJoCo reads at most 496" in error.message
    assert "starts body 497" in error.message and "not a fault in the file" in error.hint
    with pytest.raises(ModelError) as from_bodies:
        refuse_deep_bodies(robot, build_bodies(robot, fuse_static=True))
    assert from_bodies.value.one_line() == error.one_line()


def test_a_chain_as_deep_as_the_limit_passes():
    robot = parse_urdf(snake_urdf(MAX_BODY_DEPTH).encode(), "snake.urdf")
    refuse_deep_chains(robot)
    refuse_deep_bodies(robot, build_bodies(robot, fuse_static=False))


def test_fixed_joints_count_only_where_they_are_not_fused():
    robot = parse_urdf(snake_urdf(2 * MAX_BODY_DEPTH - 1, fixed_every=2).encode(), "snake.urdf")
    refuse_deep_chains(robot)  # 495 moving joints below the root: fused, 496 bodies fit
    refuse_deep_bodies(robot, build_bodies(robot, fuse_static=True))
    with pytest.raises(ModelError, match="nests bodies 991 deep"):
        refuse_deep_bodies(robot, build_bodies(robot, fuse_static=False))


def test_a_world_root_is_the_world_body_not_a_nested_one():
    text = snake_urdf(MAX_BODY_DEPTH + 1).replace('"l0"', '"world"')
    robot = parse_urdf(text.encode(), "snake.urdf")
    refuse_deep_chains(robot)
    refuse_deep_bodies(robot, build_bodies(robot, fuse_static=True))
