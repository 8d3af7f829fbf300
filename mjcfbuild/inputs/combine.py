"""Combining inputs from the URDF, an inputs file and robot.yaml into one set.

Precedence, lowest first: ``<mujoco_inputs>`` in the URDF, the inputs file, robot.yaml. When
two places say the same thing (the same named raw element, the same option attribute, a camera
or lidar of the same name, the same attribute of the same modified element, the same mesh to
decompose, a scene), the higher one wins and the build warns, naming both places. How the
processed items of each tag combine is the tag's own (``ProcessedInput.combine``).
"""

from __future__ import annotations

from lxml import etree

from mjcfbuild.inputs.model import SINGLE_SECTIONS, Inputs, RawElement
from mjcfbuild.inputs.processed import PROCESSED_INPUTS


def combine(sources: list[Inputs]) -> tuple[Inputs, list[str]]:
    """One set of inputs from ``sources`` given lowest precedence first; and the warnings."""
    warnings: list[str] = []
    combined = Inputs()
    combined.raw = _combine_raw([item for s in sources for item in s.raw], warnings)
    for kind in PROCESSED_INPUTS:
        combined.processed += kind.combine([i for s in sources for i in s.of(kind)], warnings)
    scenes = [s.scene for s in sources if s.scene is not None]
    if len(scenes) > 1:
        warnings.append(
            f"scene given in {scenes[-2].origin} and {scenes[-1].origin}; "
            f"using the one in {scenes[-1].origin}"
        )
    combined.scene = scenes[-1] if scenes else None
    return combined, warnings


def raw_identity(item: RawElement) -> tuple:
    """What makes two raw elements 'the same thing'."""
    element = etree.fromstring(item.xml)
    if item.section in SINGLE_SECTIONS:
        return (item.section,)
    if item.section == "default":
        return ("default", element.tag, element.get("class", "main"))
    name = element.get("name")
    if name:
        # Actuators, sensors, tendons, equalities and keys share one namespace per section;
        # assets, custom data and contacts have one per element type.
        kind = element.tag if item.section in ("asset", "custom", "contact") else "*"
        return (item.section, kind, name)
    canonical = " ".join(f"{k}={v}" for k, v in sorted(element.attrib.items()))
    return (item.section, element.tag, canonical)


def _combine_raw(items: list[RawElement], warnings: list[str]) -> list[RawElement]:
    chosen: dict[tuple, RawElement] = {}
    for item in items:
        identity = raw_identity(item)
        previous = chosen.get(identity)
        if previous is not None and item.section in SINGLE_SECTIONS:
            item = _merge_single(previous, item, warnings)
        elif previous is not None:
            label = identity[2] if identity[1] == "*" else f"{identity[1]} {identity[2]}"
            warnings.append(
                f"raw {item.section} '{label}' given in {previous.origin} and {item.origin}; "
                f"using the one in {item.origin}"
            )
        chosen[identity] = item
    return list(chosen.values())


def _merge_single(low: RawElement, high: RawElement, warnings: list[str]) -> RawElement:
    """An <option>-like section with the attributes of both, ``high`` winning."""
    merged = etree.fromstring(low.xml)
    override = etree.fromstring(high.xml)
    for key, value in override.attrib.items():
        if key in merged.attrib:
            warnings.append(
                f"{low.section} {key} given in {low.origin} and {high.origin}; "
                f"using {value!r} from {high.origin}"
            )
        merged.set(key, value)
    for child in override:
        merged.append(child)
    text = etree.tostring(merged, encoding="unicode")
    return RawElement(high.section, text, high.origin, lines_kept=False)
