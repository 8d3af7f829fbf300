"""Rotation and transform arithmetic, checked against independent constructions."""

from __future__ import annotations

import math
import random

import pytest

from mjcfbuild.urdf.model import Pose
from mjcfbuild.urdf.transforms import (
    Transform,
    axis_angle_matrix,
    matmul,
    matrix_to_quat,
    matrix_to_rpy,
    quat_to_matrix,
    rotation_angle_between,
    rpy_to_matrix,
)


def close(a, b, tol=1e-12):
    pairs = zip(a, b, strict=True)
    return all(abs(x - y) <= tol for ra, rb in pairs for x, y in zip(ra, rb, strict=True))


def test_rpy_is_fixed_axes_x_then_y_then_z():
    roll, pitch, yaw = 0.3, -0.7, 1.9
    expected = matmul(
        axis_angle_matrix((0, 0, 1), yaw),
        matmul(axis_angle_matrix((0, 1, 0), pitch), axis_angle_matrix((1, 0, 0), roll)),
    )
    assert close(rpy_to_matrix((roll, pitch, yaw)), expected)


@pytest.mark.parametrize("seed", range(20))
def test_round_trips(seed):
    rng = random.Random(seed)
    rpy = (rng.uniform(-3, 3), rng.uniform(-1.5, 1.5), rng.uniform(-3, 3))
    matrix = rpy_to_matrix(rpy)
    assert close(rpy_to_matrix(matrix_to_rpy(matrix)), matrix)
    assert close(quat_to_matrix(matrix_to_quat(matrix)), matrix)


def test_gimbal_lock_rpy_still_gives_the_same_rotation():
    matrix = rpy_to_matrix((0.4, math.pi / 2, -0.2))
    assert close(rpy_to_matrix(matrix_to_rpy(matrix)), matrix, 1e-9)


@pytest.mark.parametrize("distance", [0.0, 1e-11, 1e-9, 1e-7, 1e-5])
def test_near_gimbal_lock_rpy_of_a_slightly_noisy_matrix_rebuilds_it(distance):
    """Matrices read from files carry rounding noise; near the lock, roll and yaw found
    separately were off by up to a half turn. Yaw found given roll rebuilds the matrix."""
    rng = random.Random(3)
    for _ in range(2000):
        pitch = rng.choice([1, -1]) * (math.pi / 2 - distance)
        exact = rpy_to_matrix((rng.uniform(-3, 3), pitch, rng.uniform(-3, 3)))
        noisy = tuple(tuple(v + rng.uniform(-1e-12, 1e-12) for v in row) for row in exact)
        assert rotation_angle_between(rpy_to_matrix(matrix_to_rpy(noisy)), exact) < 1e-10


def test_compose_and_inverse():
    a = Transform.from_pose(Pose((1, 2, 3), (0.1, 0.2, 0.3)))
    b = Transform.from_pose(Pose((-1, 0.5, 2), (-0.4, 0.0, 1.0)))
    identity = a.compose(b).compose(b.inverse()).compose(a.inverse())
    assert identity.is_identity or close(identity.rotation, Transform().rotation, 1e-12)
    assert max(abs(v) for v in identity.position) < 1e-12


def test_rotation_angle_between_is_accurate_for_small_angles():
    a = rpy_to_matrix((0.1, 0.2, 0.3))
    b = matmul(a, axis_angle_matrix((1, 2, 3), 1e-7))
    assert rotation_angle_between(a, b) == pytest.approx(1e-7, rel=1e-6)
