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
    # The floating root's joint names: virtual joints, and joints with a whole pose as value.
    floating: list[str] = field(default_factory=list)
    discovered: bool = False  # found beside the description: only its poses are used
    # state -> joint -> the line of its <joint> element
    lines: dict[str, dict[str, int]] = field(default_factory=dict)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)

    @staticmethod
    def from_dict(data: dict) -> Srdf:
        """Rebuild from :meth:`to_dict`."""
        return Srdf(
            data["label"],
            [DisabledPair(**p) for p in data["pairs"]],
            data["states"],
            data.get("floating", []),
            data.get("discovered", False),
            data.get("lines", {}),
        )


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
    floating = {
        element.get("name", "")
        for element in root.iter("virtual_joint")
        if element.get("type") in ("floating", "planar")
    }
    for state in root.iter("group_state"):
        values: dict[str, float] = {}
        for joint in state.iter("joint"):
            words = (joint.get("value") or "").replace(",", " ").split()
            if len(words) > 1:  # a whole pose: the floating root (the model's free joint)
                floating.add(joint.get("name", ""))
                continue
            try:
                values[joint.get("name", "")] = float(words[0])
                if joint.sourceline:
                    lines = result.lines.setdefault(state.get("name", ""), {})
                    lines[joint.get("name", "")] = joint.sourceline
            except (ValueError, IndexError):
                raise InputError(
                    f"joint '{joint.get('name')}' has no numeric value",
                    file=label,
                    line=joint.sourceline,
                    hint='write value="<number>"',
                ) from None
        result.states.setdefault(state.get("name", ""), {}).update(values)
    result.floating = sorted(floating)
    return result


def home_state(
    srdf: Srdf, joints: set[str], name: str | None, floating_robot: bool
) -> tuple[str | None, dict[str, float] | None]:
    """The group_state that is the home pose, and its name: the one called ``name`` where the
    SRDF has it, else, for a floating robot, its standing pose
    (:func:`~mjcfbuild.selfcollision.discover.standing_state`). Root joints are left out; a
    named state naming another unknown joint is an error, a found one is skipped."""
    from mjcfbuild.selfcollision.discover import standing_state
    from mjcfbuild.sources.packages import did_you_mean, listing

    floating = set(srdf.floating)
    chosen = name if name in srdf.states and not srdf.discovered else None
    if chosen is None and floating_robot:
        chosen = standing_state(srdf.states, joints, floating)
    if chosen is None:
        return None, None
    state = {joint: value for joint, value in srdf.states[chosen].items() if joint not in floating}
    unknown = sorted(set(state) - joints)
    if unknown:
        raise InputError(
            f"group_state '{chosen}' names joint '{unknown[0]}', which the robot does not have"
            f"{did_you_mean(unknown[0], joints)}",
            file=srdf.label,
            line=srdf.lines.get(chosen, {}).get(unknown[0]),
            hint=f"joints: {listing(sorted(joints))}; name the root joint in a "
            '<virtual_joint type="floating"> if it is the floating base',
        )
    return chosen, state
