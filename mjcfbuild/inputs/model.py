"""MuJoCo inputs of one source: raw sections, processed items (inputs.processed), a scene;
each item with the place it came from."""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass, field
from typing import TypeVar

from mjcfbuild.inputs.processed import ProcessedInput, processed_from_dict

_Item = TypeVar("_Item", bound=ProcessedInput)

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
    # Whether ``xml`` keeps the line breaks of the element at ``origin`` (not one merged from
    # two inputs), so that a child's line there is the origin's plus its line in ``xml``.
    lines_kept: bool = True


@dataclass
class SceneInput:
    """Children of a ``<scene>`` block, copied into scene.xml."""

    xml: str
    origin: str


@dataclass
class Inputs:
    """Everything one source (URDF, inputs file, robot.yaml) adds to the model."""

    raw: list[RawElement] = field(default_factory=list)
    processed: list[ProcessedInput] = field(default_factory=list)
    scene: SceneInput | None = None

    def of(self, kind: type[_Item]) -> list[_Item]:
        """The processed items of one tag, in the order given."""
        return [item for item in self.processed if isinstance(item, kind)]

    def is_empty(self) -> bool:
        """Whether the source adds nothing."""
        return not (self.raw or self.processed or self.scene)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return {
            "raw": [asdict(item) for item in self.raw],
            "processed": [item.to_dict() for item in self.processed],
            "scene": asdict(self.scene) if self.scene else None,
        }


def inputs_from_dict(data: dict) -> Inputs:
    """Rebuild :class:`Inputs` from :meth:`Inputs.to_dict`."""
    return Inputs(
        raw=[RawElement(**d) for d in data.get("raw", [])],
        processed=[processed_from_dict(d) for d in data.get("processed", [])],
        scene=SceneInput(**data["scene"]) if data.get("scene") else None,
    )
