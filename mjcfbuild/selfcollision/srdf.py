"""Reading an SRDF: MoveIt's ``<disable_collisions>`` pairs and ``<group_state>`` poses."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

from mjcfbuild.errors import InputError


@dataclass(frozen=True)
class DisabledPair:
    """One ``<disable_collisions link1= link2= reason=>`` and its line."""

    link1: str
    link2: str
    reason: str
    line: int | None


@dataclass
class Srdf:
    """What mjcfbuild uses of an SRDF."""

    label: str
    pairs: list[DisabledPair] = field(default_factory=list)
    states: dict[str, dict[str, float]] = field(default_factory=dict)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)

    @staticmethod
    def from_dict(data: dict) -> Srdf:
        """Rebuild from :meth:`to_dict`."""
        return Srdf(data["label"], [DisabledPair(**p) for p in data["pairs"]], data["states"])


def parse_srdf(text: bytes, label: str) -> Srdf:
    """The disabled pairs and group states of SRDF ``text`` (``label`` names it in errors)."""
    from lxml import etree

    try:
        root = etree.fromstring(text, etree.XMLParser(resolve_entities=False, no_network=True))
    except etree.XMLSyntaxError as exc:
        line = exc.lineno if exc.lineno else None
        raise InputError(
            f"not valid XML: {exc.msg}", file=label, line=line, hint="fix the SRDF"
        ) from None
    if root.tag != "robot":
        raise InputError(
            f"the root element is <{root.tag}>, not <robot>",
            file=label,
            line=root.sourceline,
            hint="self_collision.srdf must name an SRDF file",
        )
    result = Srdf(label)
    for element in root.iter("disable_collisions"):
        link1, link2 = element.get("link1"), element.get("link2")
        if not link1 or not link2:
            raise InputError(
                "<disable_collisions> needs link1 and link2",
                file=label,
                line=element.sourceline,
                hint="name both links of the pair",
            )
        result.pairs.append(
            DisabledPair(link1, link2, element.get("reason") or "SRDF", element.sourceline)
        )
    for state in root.iter("group_state"):
        values: dict[str, float] = {}
        for joint in state.iter("joint"):
            try:
                values[joint.get("name", "")] = float((joint.get("value") or "").split()[0])
            except (ValueError, IndexError):
                raise InputError(
                    f"joint '{joint.get('name')}' has no numeric value",
                    file=label,
                    line=joint.sourceline,
                    hint='write value="<number>"',
                ) from None
        result.states.setdefault(state.get("name", ""), {}).update(values)
    return result
