"""Rigid transforms in plain Python floats: URDF poses, quaternions, composition.

Written without numpy or MuJoCo on purpose: the same code places fused links and checks a built
model's kinematics, and that check must not share code with MuJoCo's own URDF import.
Quaternions are (w, x, y, z), as MuJoCo writes them.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from mjcfbuild.urdf.model import Pose, Vec3

Matrix = tuple[Vec3, Vec3, Vec3]
Quat = tuple[float, float, float, float]

IDENTITY: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def vec3(values: Iterable[float]) -> Vec3:
    """Three values as a ``Vec3`` (a tuple of exactly three)."""
    x, y, z = values
    return (x, y, z)


def matrix3(rows: Iterable[Iterable[float]]) -> Matrix:
    """Three rows of three values as a ``Matrix``.

    Each row is read as it comes, so rows that are generators over a shared loop variable
    (``(... for j in ...) for i in ...``) see the right one.
    """
    a, b, c = (vec3(row) for row in rows)
    return (a, b, c)


def rpy_to_matrix(rpy: Vec3) -> Matrix:
    """URDF roll-pitch-yaw (fixed axes x, then y, then z) as a rotation matrix."""
    roll, pitch, yaw = rpy
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def matrix_to_rpy(m: Matrix) -> Vec3:
    """Roll-pitch-yaw of a rotation matrix (any of the equivalent ones at gimbal lock).

    Near gimbal lock (pitch close to +/-90 degrees) roll and yaw are each ill-conditioned, but
    their combination is not: yaw is computed from the matrix *given* the roll found, so the
    three angles rebuild the matrix to rounding error, however close to the lock it is.
    """
    pitch = math.atan2(-m[2][0], math.hypot(m[0][0], m[1][0]))
    roll = math.atan2(m[2][1], m[2][2]) if math.hypot(m[2][1], m[2][2]) > 1e-300 else 0.0
    cr, sr = math.cos(roll), math.sin(roll)
    # R * Rx(roll)^T * e_y = Rz(yaw) * e_y = (-sin(yaw), cos(yaw), 0)
    yaw = math.atan2(-(m[0][1] * cr - m[0][2] * sr), m[1][1] * cr - m[1][2] * sr)
    return (roll, pitch, yaw)


def matrix_to_quat(m: Matrix) -> Quat:
    """Unit quaternion (w, x, y, z) of a rotation matrix, with w >= 0."""
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2.0 * math.sqrt(trace + 1.0)
        q = (0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s)
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2])
        q = ((m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s)
    elif m[1][1] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2])
        q = ((m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1])
        q = ((m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s)
    norm = math.sqrt(sum(c * c for c in q))
    w, x, y, z = (c / norm for c in q)
    return (w, x, y, z) if w >= 0 else (-w, -x, -y, -z)


def quat_to_matrix(q: Quat) -> Matrix:
    """Rotation matrix of a quaternion (w, x, y, z); the quaternion need not be unit length."""
    norm = math.sqrt(sum(c * c for c in q))
    w, x, y, z = (c / norm for c in q)
    return (
        (1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
        (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
        (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)),
    )


def axis_angle_matrix(axis: Vec3, angle: float) -> Matrix:
    """Rotation by ``angle`` about ``axis`` (normalised here)."""
    norm = math.sqrt(sum(a * a for a in axis))
    x, y, z = (a / norm for a in axis)
    c, s = math.cos(angle), math.sin(angle)
    t = 1 - c
    return (
        (t * x * x + c, t * x * y - s * z, t * x * z + s * y),
        (t * x * y + s * z, t * y * y + c, t * y * z - s * x),
        (t * x * z - s * y, t * y * z + s * x, t * z * z + c),
    )


def matmul(a: Matrix, b: Matrix) -> Matrix:
    """Product of two 3x3 matrices."""
    return matrix3((sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def transpose(m: Matrix) -> Matrix:
    """Transpose (the inverse, for a rotation)."""
    return matrix3((m[j][i] for j in range(3)) for i in range(3))


def apply(m: Matrix, v: Vec3) -> Vec3:
    """Matrix times vector."""
    return vec3(sum(m[i][k] * v[k] for k in range(3)) for i in range(3))


def rotation_angle_between(a: Matrix, b: Matrix) -> float:
    """The angle (radians) of the rotation that takes ``a`` to ``b``."""
    r = matmul(transpose(a), b)
    cos = max(-1.0, min(1.0, (r[0][0] + r[1][1] + r[2][2] - 1.0) / 2.0))
    if cos > 0.99:
        # acos loses precision near 0; use the skew part instead
        skew = (r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1])
        return math.asin(min(1.0, 0.5 * math.sqrt(sum(s * s for s in skew))))
    return math.acos(cos)


@dataclass(frozen=True)
class Transform:
    """A rigid transform: ``rotation`` then translation by ``position``."""

    rotation: Matrix = IDENTITY
    position: Vec3 = (0.0, 0.0, 0.0)

    @staticmethod
    def from_pose(pose: Pose) -> Transform:
        """The transform of a URDF ``<origin>``."""
        return Transform(rpy_to_matrix(pose.rpy), vec3(float(v) for v in pose.xyz))

    @staticmethod
    def from_quat(position: Vec3, quat: Quat) -> Transform:
        """The transform of a MuJoCo ``pos``/``quat`` pair."""
        return Transform(quat_to_matrix(quat), vec3(position))

    def compose(self, other: Transform) -> Transform:
        """``self * other``: ``other`` expressed in this transform's parent frame."""
        position = apply(self.rotation, other.position)
        return Transform(
            matmul(self.rotation, other.rotation),
            vec3(self.position[i] + position[i] for i in range(3)),
        )

    def inverse(self) -> Transform:
        """The inverse transform."""
        rt = transpose(self.rotation)
        p = apply(rt, self.position)
        return Transform(rt, (-p[0], -p[1], -p[2]))

    def to_pose(self) -> Pose:
        """As a URDF pose."""
        return Pose(self.position, matrix_to_rpy(self.rotation))

    @property
    def quat(self) -> Quat:
        """The rotation as a quaternion (w, x, y, z)."""
        return matrix_to_quat(self.rotation)

    @property
    def is_identity(self) -> bool:
        """Whether this is (numerically) the identity."""
        return all(abs(v) < 1e-15 for v in self.position) and all(
            abs(self.rotation[i][j] - IDENTITY[i][j]) < 1e-15 for i in range(3) for j in range(3)
        )
