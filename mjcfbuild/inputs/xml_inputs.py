"""Reading the reference converter's ``<mujoco_inputs>`` format, from a URDF or its own file.

    <mujoco_inputs>
      <raw_inputs> option, default, asset, actuator, tendon, ... copied into the model </raw_inputs>
      <processed_inputs> camera, lidar, decompose_mesh, modify_element </processed_inputs>
      <scene> statistic, visual, asset, worldbody ... copied into scene.xml </scene>
    </mujoco_inputs>

Every item keeps ``file:line`` so later errors point at it. The processed elements are read
by their models (``inputs.processed``).
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from mjcfbuild.errors import InputError
from mjcfbuild.inputs.model import RAW_SECTIONS, SINGLE_SECTIONS, Inputs, RawElement, SceneInput
from mjcfbuild.inputs.processed import PROCESSED_INPUTS, processed_tag
from mjcfbuild.urdf.parse import parse_xml


def read_inputs_file(path: Path, label: str) -> Inputs:
    """A separate inputs file: ``<mujoco_inputs>`` at its root, or a URDF that holds one."""
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read inputs file: {exc.strerror}", file=label) from None
    warnings: list[str] = []
    root = parse_xml(data, label, warnings)
    if root.tag == "robot":
        return inputs_in_urdf(root, label)
    if root.tag != "mujoco_inputs":
        raise InputError(
            f"the root element is <{root.tag}>; an inputs file holds <mujoco_inputs> "
            "(or is a URDF containing one)",
            file=label,
            line=root.sourceline,
        )
    return read_mujoco_inputs(root, label)


def inputs_in_urdf(root: etree._Element, label: str) -> Inputs:
    """The ``<mujoco_inputs>`` of a parsed URDF (empty inputs if it has none)."""
    found = root.findall("mujoco_inputs")
    if len(found) > 1:
        raise InputError(
            "the URDF has more than one <mujoco_inputs>", file=label, line=found[1].sourceline
        )
    return read_mujoco_inputs(found[0], label) if found else Inputs()


def read_mujoco_inputs(element: etree._Element, label: str) -> Inputs:
    """Parse one ``<mujoco_inputs>`` element."""
    inputs = Inputs()
    seen: set[str] = set()
    for child in _elements(element):
        if child.tag not in ("raw_inputs", "processed_inputs", "scene"):
            raise _error(
                label,
                child,
                f"<mujoco_inputs> cannot hold <{child.tag}>",
                "use raw_inputs, processed_inputs and scene",
            )
        if child.tag in seen:
            raise _error(label, child, f"<mujoco_inputs> has more than one <{child.tag}>")
        seen.add(child.tag)
        if child.tag == "raw_inputs":
            inputs.raw = read_raw_sections(child, label)
        elif child.tag == "processed_inputs":
            _processed(child, label, inputs)
        else:
            xml = "".join(_xml(grandchild) for grandchild in _elements(child))
            inputs.scene = SceneInput(xml, _origin(label, child))
    return inputs


def _elements(element: etree._Element):
    return [child for child in element if isinstance(child.tag, str)]


def _xml(element: etree._Element) -> str:
    return etree.tostring(element, encoding="unicode", with_tail=False)


def _origin(label: str, element: etree._Element) -> str:
    return f"{label}:{element.sourceline}" if element.sourceline else label


def _error(label: str, element: etree._Element, message: str, hint: str | None = None):
    return InputError(message, file=label, line=element.sourceline, hint=hint)


def read_raw_sections(element: etree._Element, label: str) -> list[RawElement]:
    """The sections under ``element`` (a ``<raw_inputs>``) as raw elements."""
    result = []
    for section in _elements(element):
        if section.tag not in RAW_SECTIONS:
            raise _error(
                label,
                section,
                f"raw_inputs cannot hold <{section.tag}>",
                f"allowed: {', '.join(RAW_SECTIONS)}",
            )
        if section.tag in SINGLE_SECTIONS:
            result.append(RawElement(section.tag, _xml(section), _origin(label, section)))
            continue
        for child in _elements(section):
            result.append(RawElement(section.tag, _xml(child), _origin(label, child)))
    return result


def _processed(element: etree._Element, label: str, inputs: Inputs) -> None:
    for child in _elements(element):
        kind = processed_tag(child.tag)
        if kind is None:
            raise _error(
                label,
                child,
                f"processed_inputs cannot hold <{child.tag}>",
                f"allowed: {', '.join(kind.xml_tag for kind in PROCESSED_INPUTS)}",
            )
        inputs.processed.append(kind.from_xml(child, label))
