"""The evidence a robot gives about which way up each of its mesh files is.

For each shape that uses a mesh, what ought to lie in or near the mesh, in the mesh file's own
frame: its link's joint origin, child joints' origins and centre of mass, and the boxes of the
link's authored collision primitives. :mod:`mjcfbuild.meshes.upaxis` decides from it; this is
plain Python, called by the task graph while it plans.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from mjcfbuild.meshes.upaxis import MeshUse
from mjcfbuild.urdf.transforms import Matrix, apply, rpy_to_matrix, transpose

if TYPE_CHECKING:
    from mjcfbuild.urdf.model import Geometry, Robot, Vec3

_PRIMITIVES = ("box", "cylinder", "sphere", "capsule")


def mesh_uses(robot: Robot, mesh_id: str) -> list[MeshUse]:
    """The evidence of every shape (visual or collision) of ``robot`` that uses ``mesh_id``."""
    children = robot.child_joints()
    parents = robot.parent_joint()
    uses = []
    for link in robot.links:
        for shape in link.shapes:
            geometry = shape.geometry
            if geometry.kind != "mesh" or geometry.mesh_id != mesh_id:
                continue
            rotation = rpy_to_matrix(shape.origin.rpy)
            into_mesh = _into_mesh_frame(shape.origin.xyz, rotation, geometry)
            if into_mesh is None:
                continue
            points: list[list[float]] = []
            kinds: list[str] = []
            if link.name in parents:
                points.append(into_mesh((0.0, 0.0, 0.0)))
                kinds.append("joint")
            for joint in children.get(link.name, []):
                points.append(into_mesh(joint.origin.xyz))
                kinds.append("child joint")
            if link.inertial is not None and link.inertial.mass > 0:
                points.append(into_mesh(link.inertial.origin.xyz))
                kinds.append("centre of mass")
            boxes = []
            for other in link.collisions:
                if other.geometry.kind in _PRIMITIVES and all(v > 0 for v in other.geometry.size):
                    corners = _corners(other.origin.xyz, other.origin.rpy, other.geometry)
                    moved = [into_mesh(c) for c in corners]
                    boxes.append(
                        [[min(p[i] for p in moved) for i in range(3)],
                         [max(p[i] for p in moved) for i in range(3)]]
                    )  # fmt: skip
            use = MeshUse(link.name, points, kinds, boxes)
            if not use.empty:
                uses.append(use)
    return uses


def _into_mesh_frame(
    xyz: Vec3, rotation: Matrix, geometry: Geometry
) -> Callable[[Sequence[float]], list[float]] | None:
    scale = geometry.scale
    if any(abs(s) < 1e-12 for s in scale):
        return None
    back = transpose(rotation)

    def into(point: Sequence[float]) -> list[float]:
        local = apply(back, (point[0] - xyz[0], point[1] - xyz[1], point[2] - xyz[2]))
        return [local[i] / scale[i] for i in range(3)]

    return into


def _corners(xyz: Vec3, rpy: Vec3, geometry: Geometry) -> list[tuple[float, float, float]]:
    size = geometry.size
    if geometry.kind == "box":
        half = (size[0] / 2, size[1] / 2, size[2] / 2)
    elif geometry.kind == "sphere":
        half = (size[0],) * 3
    elif geometry.kind == "cylinder":
        half = (size[0], size[0], size[1] / 2)
    else:  # capsule: radius, length between the caps' centres
        half = (size[0], size[0], size[1] / 2 + size[0])
    rotation = rpy_to_matrix(rpy)
    corners = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                local = apply(rotation, (sx * half[0], sy * half[1], sz * half[2]))
                corners.append((local[0] + xyz[0], local[1] + xyz[1], local[2] + xyz[2]))
    return corners
