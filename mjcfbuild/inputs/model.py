"""MuJoCo inputs as plain data, each item with the place it came from."""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass, field

# raw_inputs sections and whether a section holds named children merged one by one
# (actuator, sensor, ...) or is one element whose attributes merge (option, visual, ...).
LIST_SECTIONS = (
    "default",
    "asset",
    "actuator",
    "tendon",
    "equality",
    "sensor",
    "contact",
    "keyframe",
    "custom",
)
SINGLE_SECTIONS = ("option", "size", "visual", "statistic")
RAW_SECTIONS = (*SINGLE_SECTIONS, *LIST_SECTIONS)


def origin_location(origin: str) -> tuple[str, int | None]:
    """The file and line of an origin like ``inputs.xml:12`` (line None if it has none)."""
    match = re.match(r"^(.*):(\d+)$", origin)
    if match:
        return match.group(1), int(match.group(2))
    return origin, None


@dataclass
class RawElement:
    """One element of ``raw_inputs``: a child of a list section, or a single section."""

    section: str
    xml: str
    origin: str


@dataclass
class CameraInput:
    """A camera at a link, looking along the link's +z like a ROS optical frame."""

    name: str
    link: str
    attributes: dict[str, str]
    origin: str


@dataclass
class LidarInput:
    """A planar lidar as a fan of rangefinders about the link's +z axis."""

    sensor_name: str
    link: str
    min_angle: float
    max_angle: float
    angle_increment: float
    origin: str


@dataclass
class ModifyInput:
    """Attributes set on a generated element, found by type and name (or geom by mesh, class)."""

    type: str
    attributes: dict[str, str]
    origin: str
    name: str | None = None
    mesh: str | None = None
    geom_class: str | None = None

    def target(self) -> str:
        """How the target is named in messages."""
        if self.type == "geom":
            return f"geom with mesh '{self.mesh}' and class '{self.geom_class}'"
        return f"{self.type} '{self.name}'"


@dataclass
class DecomposeInput:
    """Decompose a mesh with CoACD (the reference converter's ``decompose_mesh``)."""

    mesh: str
    threshold: float
    origin: str


@dataclass
class SceneInput:
    """Children of a ``<scene>`` block, copied into scene.xml."""

    xml: str
    origin: str


@dataclass
class Inputs:
    """Everything one source (URDF, inputs file, robot.yaml) adds to the model."""

    raw: list[RawElement] = field(default_factory=list)
    cameras: list[CameraInput] = field(default_factory=list)
    lidars: list[LidarInput] = field(default_factory=list)
    modifications: list[ModifyInput] = field(default_factory=list)
    decompositions: list[DecomposeInput] = field(default_factory=list)
    scene: SceneInput | None = None

    def is_empty(self) -> bool:
        """Whether the source adds nothing."""
        return not (
            self.raw
            or self.cameras
            or self.lidars
            or self.modifications
            or self.decompositions
            or self.scene
        )

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)


def inputs_from_dict(data: dict) -> Inputs:
    """Rebuild :class:`Inputs` from :meth:`Inputs.to_dict`."""
    return Inputs(
        raw=[RawElement(**d) for d in data.get("raw", [])],
        cameras=[CameraInput(**d) for d in data.get("cameras", [])],
        lidars=[LidarInput(**d) for d in data.get("lidars", [])],
        modifications=[ModifyInput(**d) for d in data.get("modifications", [])],
        decompositions=[DecomposeInput(**d) for d in data.get("decompositions", [])],
        scene=SceneInput(**data["scene"]) if data.get("scene") else None,
    )
