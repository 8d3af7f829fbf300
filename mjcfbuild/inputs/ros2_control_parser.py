"""What ros2_control's parser requires of a ``<ros2_control>`` block's elements before any
hardware starts (hardware_interface's component_parser.cpp, ``parse_resource_from_xml`` and the
functions it calls): each rule here is one of its ``get_attribute_value`` or
``get_text_for_element`` calls, which stop the controller manager on a description that lacks
what they read."""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree


@dataclass(frozen=True)
class ParserRefusal:
    """An element of a block ros2_control's parser stops at."""

    origin: str  # "file:line"
    what: str  # what the element lacks, as a user reads it
    said: str  # what the parser says (its exception's text), or what happens
    fix: str
    nameless: str = ""  # the tag of an element without a name attribute


def block_refusals(block: etree._Element, label: str) -> list[ParserRefusal]:
    """Every element of ``block`` (a ``<ros2_control>``) the parser stops at, in document order."""
    found: list[ParserRefusal] = []

    def at(element: etree._Element) -> str:
        return f"{label}:{element.sourceline}"

    # parse_resource_from_xml: the block's name and type
    for attribute, example in (("name", 'name="my_robot"'), ("type", 'type="system"')):
        if block.get(attribute) is None:
            found.append(
                ParserRefusal(
                    at(block),
                    f"<ros2_control> has no {attribute} attribute",
                    f"no attribute {attribute} in ros2_control tag",
                    f"write {example} on it",
                )
            )
    for child in block:
        if not isinstance(child.tag, str):
            continue
        if child.tag == "hardware":
            found += _hardware(child, at)
        elif child.tag in ("joint", "sensor", "gpio"):
            found += _component(child, at, own_limits=child.tag != "gpio")
        elif child.tag == "transmission":
            found += _transmission(child, at)
    if block.get("type") == "actuator":
        # auto_fill_transmission_interfaces: an actuator component's transmission
        for transmission in block.findall("transmission"):
            joints = transmission.findall("joint")
            if len(joints) != 1:
                found.append(
                    ParserRefusal(
                        at(transmission),
                        f"the transmission of an actuator block has {len(joints)} <joint>s",
                        "There should be exactly one joint defined in this component but "
                        f"found {len(joints)}",
                        'name one joint in it, or make the block type="system"',
                    )
                )
    return found


def _hardware(hardware: etree._Element, at) -> list[ParserRefusal]:
    """<hardware>: its <plugin> is read without a check that it is there (a null element's
    text: the controller manager crashes), and each <param> needs a name."""
    found = []
    if hardware.find("plugin") is None:
        found.append(
            ParserRefusal(
                at(hardware),
                "<hardware> has no <plugin>",
                "the parser reads the text of the <plugin> it did not find: the controller "
                "manager crashes",
                "add <plugin>mujoco_ros2_control/MujocoSystemInterface</plugin>",
            )
        )
    return found + _params(hardware, at)


def _component(component: etree._Element, at, own_limits: bool) -> list[ParserRefusal]:
    """<joint>, <sensor> and <gpio> (parse_component_from_xml, and for a <gpio> its complex
    form, which reads no <limits> of its own): a name, each interface's name, each <limits>'
    enable, each <param>'s name."""
    found = []
    if component.get("name") is None:
        found.append(_nameless(component, at))
    for interface in [
        *component.findall("command_interface"),
        *component.findall("state_interface"),
    ]:
        if interface.get("name") is None:
            found.append(_nameless(interface, at))
        found += _params(interface, at) + _limits(interface, at)
    return found + _params(component, at) + (_limits(component, at) if own_limits else [])


def _transmission(transmission: etree._Element, at) -> list[ParserRefusal]:
    """parse_transmission_from_xml: its name, each <joint>'s and <actuator>'s name (read before
    their role), each <param>'s name."""
    parts = [transmission, *transmission.findall("joint"), *transmission.findall("actuator")]
    nameless = [_nameless(part, at) for part in parts if part.get("name") is None]
    return nameless + _params(transmission, at)


def _nameless(element: etree._Element, at) -> ParserRefusal:
    tag = element.tag
    return ParserRefusal(
        at(element),
        f"<{tag}> has no name attribute",
        f"no attribute name in {tag} tag",
        'write name="..." on it',
        nameless=tag,
    )


def _params(element: etree._Element, at) -> list[ParserRefusal]:
    """parse_parameters_from_xml: every <param> of ``element`` needs a name."""
    return [
        ParserRefusal(
            at(param),
            "<param> has no name attribute",
            "no parameter name attribute set in param tag",
            'write name="..." on it',
        )
        for param in element.findall("param")
        if param.get("name") is None
    ]


def _limits(element: etree._Element, at) -> list[ParserRefusal]:
    """parse_component_from_xml and parse_interfaces_from_xml: the first <limits> is read for
    its enable attribute."""
    limits = element.find("limits")
    if limits is None or limits.get("enable") is not None:
        return []
    return [
        ParserRefusal(
            at(limits),
            "<limits> has no enable attribute",
            "no attribute enable in limits tag",
            'write enable="true" or enable="false" on it, or remove it',
        )
    ]
