"""Which way up a COLLADA file's data really is, decided from the links that use it.

A DAE file says ``<up_axis>Y_UP</up_axis>`` (or ``X_UP``), and exporters write that tag
whether or not they turned the coordinates: real packages hold files tagged Y-up with Y-up data
and files tagged Y-up with Z-up data. The tag alone cannot decide, so the links that use the
file do. For each use, the plan's robot gives what ought to lie in or near the mesh, in the
mesh file's own frame: the link's authored collision primitives (boxes, cylinders, spheres,
capsules), its centre of mass, its own joint's origin (the link frame's origin) and its child
joints' origins. The mesh is read both ways (as the coordinates stand, that is Z-up, and turned
as tagged) and each is scored by how far that evidence lies outside the mesh's bounding box and
how little the collision primitives' boxes overlap it. The file is turned only when the tagged
reading fits clearly better; with no evidence, or no clear winner, the coordinates are kept as
they are, as ROS tools draw them.

:func:`mjcfbuild.urdf.mesh_uses.mesh_uses` gathers the evidence from the robot in plain Python
(the task graph calls it while planning); :func:`decide` needs numpy and runs in the mesh step.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.records import Record

if TYPE_CHECKING:
    import numpy as np

# Turn only when the tagged reading's misfit is at most this fraction of the untouched one's,
# the untouched one misfits by at least MIN_MISFIT, and the tagged one fits well (at most
# FIT_PER_ITEM per point or box): a clear verdict, never a coin toss between two bad fits.
CLEAR_RATIO = 0.5
MIN_MISFIT = 0.25
FIT_PER_ITEM = 0.5


@dataclass(frozen=True)
class MeshUse(Record):
    """What one link that uses a mesh says about it, in the mesh file's frame (unscaled).

    ``points``: joint origins and the centre of mass, which should lie in or near the mesh;
    ``boxes``: the ``[low, high]`` corners of each authored collision primitive's bounding box,
    which should overlap the mesh's."""

    link: str
    points: list[list[float]]
    kinds: list[str]  # per point: "joint", "child joint" or "centre of mass"
    boxes: list[list[list[float]]]

    @property
    def empty(self) -> bool:
        """Whether the use says nothing about the mesh."""
        return not self.points and not self.boxes


@dataclass(frozen=True)
class UpAxisDecision(Record):
    """What was done with a DAE file's up axis, and why."""

    tag: str
    turned: bool
    reason: str


def read_up_axis(path: Path) -> str:
    """The ``<up_axis>`` a DAE file declares (COLLADA's default, ``Y_UP``, when it has none),
    read from the file's head without parsing its geometry."""
    from lxml import etree

    try:
        for _, element in etree.iterparse(str(path), events=("end",), huge_tree=True):
            name = element.tag.rsplit("}", 1)[-1] if isinstance(element.tag, str) else ""
            if name == "up_axis":
                return (element.text or "Y_UP").strip()
            if name == "asset":
                return "Y_UP"
    except (etree.XMLSyntaxError, OSError):
        return "Y_UP"  # the conversion reports the unreadable file
    return "Y_UP"


def up_rotation(tag: str) -> list[list[float]]:
    """The rotation that turns data written ``tag`` up into Z-up data."""
    if tag == "Y_UP":  # y -> z, z -> -y
        return [[1, 0, 0], [0, 0, -1], [0, 1, 0]]
    if tag == "X_UP":  # COLLADA's X_UP: right is -y, up x, in z; so x -> z, y -> -x, z -> -y
        return [[0, -1, 0], [0, 0, -1], [1, 0, 0]]
    return [[1, 0, 0], [0, 1, 0], [0, 0, 1]]


def misfit(vertices: np.ndarray, uses: list[MeshUse]) -> tuple[float, str]:
    """How badly ``vertices`` fit the evidence (0: perfectly), and a short account of it.

    Each point costs its distance outside the mesh's bounding box, in units of the box's
    diagonal; each collision box costs one minus its overlap (intersection over union) with
    the mesh's box."""
    import numpy as np

    low, high = vertices.min(axis=0), vertices.max(axis=0)
    diagonal = max(float(np.linalg.norm(high - low)), 1e-9)
    cost = 0.0
    inside = total_points = 0
    overlaps = []
    for use in uses:
        for point in use.points:
            p = np.asarray(point)
            outside = float(np.linalg.norm(np.maximum(low - p, 0) + np.maximum(p - high, 0)))
            cost += outside / diagonal
            total_points += 1
            inside += outside <= 0.05 * diagonal
        for box_low, box_high in use.boxes:
            overlap = _iou(low, high, np.asarray(box_low), np.asarray(box_high))
            overlaps.append(overlap)
            cost += 1.0 - overlap
    parts = []
    if total_points:
        parts.append(f"{inside}/{total_points} joint origins and centres of mass in or at it")
    if overlaps:
        parts.append(f"collision boxes overlap {sum(overlaps) / len(overlaps):.2f}")
    return cost, ", ".join(parts)


def _iou(low_a, high_a, low_b, high_b) -> float:
    import numpy as np

    # A flat box (a plane, a disc) has no volume: pad every box by a sliver of its size.
    pad_a = 0.01 * float(np.max(high_a - low_a))
    pad_b = 0.01 * float(np.max(high_b - low_b))
    low_a, high_a = low_a - pad_a, high_a + pad_a
    low_b, high_b = low_b - pad_b, high_b + pad_b
    common = np.clip(np.minimum(high_a, high_b) - np.maximum(low_a, low_b), 0, None)
    intersection = float(np.prod(common))
    union = float(np.prod(high_a - low_a) + np.prod(high_b - low_b)) - intersection
    return intersection / union if union > 0 else 0.0


def decide(vertices: np.ndarray, tag: str, uses: list[MeshUse]) -> UpAxisDecision:
    """Whether to turn ``vertices`` (as the file stores them, in metres) as ``tag`` says."""
    import numpy as np

    if tag not in ("Y_UP", "X_UP"):
        return UpAxisDecision(tag, False, f"tagged {tag}: nothing to turn")
    if not uses:
        return UpAxisDecision(
            tag, False, f"tagged {tag}, kept as written: no link geometry, centre of mass or "
            "joint to compare it with"
        )  # fmt: skip
    kept, kept_account = misfit(vertices, uses)
    turned, turned_account = misfit(vertices @ np.asarray(up_rotation(tag), float).T, uses)
    links = ", ".join(sorted({f"'{use.link}'" for use in uses}))
    both = (
        f"as tagged: {turned_account} (misfit {turned:.2f}); as Z-up: {kept_account} "
        f"(misfit {kept:.2f})"
    )
    items = sum(len(use.points) + len(use.boxes) for use in uses)
    if kept >= MIN_MISFIT and turned <= CLEAR_RATIO * kept and turned <= FIT_PER_ITEM * items:
        return UpAxisDecision(tag, True, f"tagged {tag}, turned to Z-up: link {links} fits it "
                              f"as tagged; {both}")  # fmt: skip
    return UpAxisDecision(
        tag, False, f"tagged {tag}, kept as written (its data is Z-up): link {links} fits it "
        f"as written; {both}" if turned > kept else f"tagged {tag}, kept as written: the "
        f"evidence of link {links} does not clearly favour turning it; {both}"
    )  # fmt: skip
