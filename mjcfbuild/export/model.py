"""What an MJCF model says that a URDF can carry: bodies, joints, geoms, sites, couplings.

The reader fills these from a compiled MuJoCo model; the URDF writer reads only these, so the
rules that turn MuJoCo's concepts into URDF's are kept apart from both.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from mjcfbuild.urdf.model import Vec3
from mjcfbuild.urdf.transforms import Matrix, Transform

if TYPE_CHECKING:
    import numpy as np

RGBA = tuple[float, float, float, float]


@dataclass
class GeomOut:
    """One geom in its body's frame. ``size`` is MuJoCo's (half sizes for boxes, half lengths
    for cylinders and capsules); ``roles`` says whether it is drawn, collides, or both."""

    kind: str
    size: tuple[float, ...]
    pose: Transform
    rgba: RGBA
    roles: tuple[str, ...]
    mesh: int | None = None


@dataclass
class JointOut:
    """One MuJoCo joint of a body: its anchor and axis in the body frame, its range measured
    from the joint's reference position (the pose the body is written in), and its top speed
    where the model knows it (rad/s or m/s; None: unknown)."""

    name: str
    kind: str  # hinge, slide, ball or free
    position: Vec3
    axis: Vec3
    limited: bool
    lower: float
    upper: float
    effort: float
    damping: float = 0.0
    friction: float = 0.0
    velocity: float | None = None


@dataclass
class BodyOut:
    """One body: where it sits in its parent at the reference pose, and what it carries."""

    name: str
    parent: str | None
    pose: Transform
    joints: list[JointOut] = field(default_factory=list)
    mass: float = 0.0
    com: Vec3 = (0.0, 0.0, 0.0)
    inertia: Matrix = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    geoms: list[GeomOut] = field(default_factory=list)
    sites: list[tuple[str, Transform]] = field(default_factory=list)


@dataclass
class MeshOut:
    """A mesh as MuJoCo compiled it (scaled, in the frame its geoms are placed in): numpy
    arrays of vertices (N, 3) and triangles (M, 3)."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray


@dataclass
class MimicOut:
    """``follower = multiplier * leader + offset``, in URDF joint coordinates."""

    follower: str
    leader: str
    multiplier: float
    offset: float


@dataclass
class ModelOut:
    """Everything the URDF writer needs, in tree order (parents before children)."""

    name: str
    bodies: list[BodyOut]
    meshes: dict[int, MeshOut]
    mimics: list[MimicOut]
    warnings: list[str] = field(default_factory=list)
