"""A mesh *product*'s summary (``products/<id>.json``), written and read here only.

:mod:`mjcfbuild.meshes.convert` makes the product's files; the summary lists them with their
digests and says which file serves which purpose.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from mjcfbuild.records import Record

PRODUCT_FORMAT = 3
# The whole mesh, when it has a single look: drawn, and collided with, from one file.
WHOLE_MESH = "mesh.obj"


@dataclass(frozen=True)
class ProductPart(Record):
    """One look (colour and texture) of a mesh, in a file of its own."""

    file: str
    rgba: list[float] | None
    texture: str | None  # a PNG in the product, if the look has one
    vertices: int
    faces: int
    volume: float  # 0 for an open shell
    emission: float | None = None  # MuJoCo's material emission: a share of its colour


@dataclass(frozen=True)
class MeshProduct(Record):
    """What a mesh file was converted into."""

    format: int
    parts: list[ProductPart]  # for drawing
    collision: str | None  # all triangles in one file, when the mesh is collision geometry
    collision_volume: float
    hull: str | None  # the convex hull, when a collision policy asks for it
    faces: int
    files: dict[str, str]  # every file of the product -> its MD5
    warnings: list[str]
    # A DAE file's up axis: meshes.upaxis.UpAxisDecision as a dict (None for other formats).
    up_axis: dict | None = None

    @property
    def collision_is_whole(self) -> bool:
        """Whether the collision mesh is the single visual file (one asset serves both)."""
        return self.collision == WHOLE_MESH

    def text(self) -> bytes:
        """The summary as the bytes of its JSON file."""
        return (json.dumps(self.to_dict(), indent=1, sort_keys=True) + "\n").encode()


def read_product(path: Path) -> MeshProduct:
    """The summary of the product in ``path``."""
    return MeshProduct.from_dict(json.loads(path.read_text()))
