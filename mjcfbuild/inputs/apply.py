"""Applying combined MuJoCo inputs to the assembled model (an lxml tree of its MJCF).

Raw sections are merged into the model's own sections: mjcfbuild's default classes take the
attributes the inputs give them (with a warning where they differ), other sections gain the
input elements. Each processed item applies itself (``inputs.processed``) through a
:class:`ModelTarget`: cameras and lidars are placed at their links with poses computed here,
modifications set attributes on generated elements. Every name an input refers to is checked
before MuJoCo sees the model, so a typo is reported at the input's line with the names that do
exist.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from lxml import etree

from mjcfbuild.actuators import ACTUATOR_TAGS
from mjcfbuild.errors import InputError
from mjcfbuild.inputs.frames import camera_pose, lidar_body_pose, ray_count
from mjcfbuild.inputs.model import SINGLE_SECTIONS, Inputs, RawElement, origin_location
from mjcfbuild.inputs.processed import PROCESSED_INPUTS, ModifyInput
from mjcfbuild.numbers import output, output_list
from mjcfbuild.sources.packages import did_you_mean
from mjcfbuild.urdf.transforms import Transform

# Where sections go in the model, in the order MJCF files conventionally list them.
SECTION_ORDER = (
    "compiler",
    "option",
    "size",
    "visual",
    "statistic",
    "default",
    "extension",
    "custom",
    "asset",
    "worldbody",
    "contact",
    "equality",
    "tendon",
    "actuator",
    "sensor",
    "keyframe",
)


@dataclass
class LinkPlace:
    """Where a URDF link is: the body holding it (None for the world) and its pose there."""

    body: str | None
    pose: Transform


@dataclass
class ApplyResult:
    """What applying inputs found worth telling the user."""

    warnings: list[str] = field(default_factory=list)
    lidar_sensors: list[str] = field(default_factory=list)


def input_error(origin: str, message: str, hint: str | None = None) -> InputError:
    """An :class:`InputError` pointing at an input's origin."""
    file, line = origin_location(origin)
    return InputError(message, file=file, line=line, hint=hint)


@dataclass
class ModelTarget:
    """The model tree processed inputs are applied to, and what they need to find their place:
    each link's place, each mesh's names."""

    root: etree._Element
    links: dict[str, LinkPlace]
    mesh_aliases: dict[str, set[str]]
    result: ApplyResult

    def add_camera(self, name: str, link: str, attributes: dict[str, str], origin: str) -> None:
        """A camera at ``link`` (a ROS optical frame), with its MuJoCo attributes."""
        place = _link(self.links, link, origin, "camera")
        _mujoco_has(attributes, "camera", f"camera '{name}'", origin)
        element = etree.Element("camera", {"name": name})
        set_pose(element, camera_pose(place.pose))
        for key, value in attributes.items():
            element.set(key, value)
        insert_in_body(body_element(self.root, place.body), element)

    def add_lidar(
        self, sensor_name: str, link: str, angles: tuple[float, float, float], origin: str
    ) -> None:
        """A lidar's rays at ``link``; the rangefinders reading them become lidar sensors."""
        place = _link(self.links, link, origin, "lidar")
        add_lidar_sites(self.root, place, f"{link}_lidar_body", sensor_name, angles)
        for sensor in self.root.iter("rangefinder"):
            if sensor.get("site") == sensor_name and sensor.get("name"):
                self.result.lidar_sensors.append(sensor.get("name"))

    def modify_targets(self, modify: ModifyInput) -> list[etree._Element]:
        """The generated elements ``modify`` names; none is an error listing those that exist."""
        return _modify_targets(self.root, modify, self.mesh_aliases)


def apply_inputs(
    root: etree._Element,
    inputs: Inputs,
    links: dict[str, LinkPlace],
    mesh_aliases: dict[str, set[str]],
) -> ApplyResult:
    """Apply ``inputs`` to the model tree ``root`` in place."""
    result = ApplyResult()
    tracked: list[tuple[etree._Element, str]] = []
    for item in inputs.raw:
        tracked += [(element, item.origin) for element in _merge_raw(root, item, result.warnings)]
    result.warnings += _drop_mimics_the_inputs_couple(root, tracked)
    target = ModelTarget(root, links, mesh_aliases, result)
    for kind in PROCESSED_INPUTS:
        for processed in inputs.of(kind):
            processed.apply(target)
    check_references(root, tracked)
    return result


def add_lidar_sites(
    root: etree._Element,
    place: LinkPlace,
    body_name: str,
    site_name: str,
    angles: tuple[float, float, float],
) -> int:
    """A body at ``place`` holding a ``<replicate>`` of rangefinder sites named
    ``site_name`` (one per ray: min_angle to max_angle by the increment, in ``angles``);
    returns how many rays."""
    min_angle, max_angle, increment = angles
    count = ray_count(min_angle, max_angle, increment)
    body = etree.Element("body", {"name": body_name})
    set_pose(body, lidar_body_pose(place.pose, min_angle))
    replicate = etree.SubElement(
        body,
        "replicate",
        {"count": str(count), "sep": "-", "offset": "0 0 0", "euler": f"0 {output(increment)} 0"},
    )
    etree.SubElement(replicate, "site", {"name": site_name})
    insert_in_body(body_element(root, place.body), body, last=True)
    return count


def _drop_mimics_the_inputs_couple(root, tracked) -> list[str]:
    """A joint equality from the inputs replaces the one mjcfbuild made of a URDF <mimic>
    for the same two joints, so the pair is not constrained twice."""
    from_inputs = {id(element) for element, _ in tracked}
    section = root.find("equality")
    if section is None:
        return []
    coupled = {
        frozenset((e.get("joint1"), e.get("joint2"))): origin
        for e, origin in tracked
        if e.tag == "joint" and e.getparent() is section
    }
    notes = []
    for element in list(section):
        pair = frozenset((element.get("joint1"), element.get("joint2")))
        if element.tag == "joint" and id(element) not in from_inputs and pair in coupled:
            section.remove(element)
            notes.append(
                f"{coupled[pair]}: the joint equality of the inputs replaces the URDF <mimic> "
                f"of {element.get('joint1')}"
            )
    return notes


def _link(links: dict[str, LinkPlace], name: str, origin: str, what: str) -> LinkPlace:
    if name not in links:
        raise input_error(
            origin,
            f"{what} refers to link '{name}', which does not exist{did_you_mean(name, set(links))}",
            hint=f"links: {_listing(links)}",
        )
    return links[name]


def _mujoco_has(attributes: Iterable[str], tag: str, what: str, origin: str) -> None:
    """Refuse, at the input's place, an attribute MuJoCo's ``<tag>`` does not have (MuJoCo
    would refuse the assembled model without saying which input set it)."""
    from mjcfbuild.inputs.mujoco_schema import mujoco_attributes

    known = mujoco_attributes(tag)
    unknown = [name for name in attributes if known and name not in known]
    if unknown:
        raise input_error(
            origin,
            f"{what} sets '{unknown[0]}', which MuJoCo's <{tag}> does not have"
            + did_you_mean(unknown[0], set(known)),
            hint=f"<{tag}> attributes: {_listing(known, limit=len(known))}",
        )


def _listing(names: Iterable[str], limit: int = 12) -> str:
    ordered = sorted(set(names))
    text = ", ".join(ordered[:limit])
    return (
        text + (f", ... ({len(ordered)} in all)" if len(ordered) > limit else "")
        if ordered
        else "none"
    )


def set_pose(element: etree._Element, pose: Transform) -> None:
    position = tuple(0.0 if abs(v) < 1e-14 else v for v in pose.position)
    quat = tuple(0.0 if abs(v) < 1e-14 else v for v in pose.quat)
    if any(position):
        element.set("pos", output_list(position))
    if quat != (1.0, 0.0, 0.0, 0.0):
        element.set("quat", output_list(quat))


def body_element(root: etree._Element, body: str | None) -> etree._Element:
    worldbody = root.find("worldbody")
    if body is None:
        return worldbody
    for element in worldbody.iter("body"):
        if element.get("name") == body:
            return element
    raise KeyError(body)


def insert_in_body(body: etree._Element, element: etree._Element, last: bool = False) -> None:
    """Add ``element`` to ``body`` before its child bodies (or after everything if ``last``)."""
    if not last:
        for index, child in enumerate(body):
            if child.tag == "body":
                body.insert(index, element)
                return
    body.append(element)


def model_section(root: etree._Element, name: str) -> etree._Element:
    existing = root.find(name)
    if existing is not None:
        return existing
    element = etree.Element(name)
    position = SECTION_ORDER.index(name)
    for index, child in enumerate(root):
        if (
            isinstance(child.tag, str)
            and child.tag in SECTION_ORDER
            and SECTION_ORDER.index(child.tag) > position
        ):
            root.insert(index, element)
            return element
    root.append(element)
    return element


def _merge_raw(root: etree._Element, item: RawElement, warnings: list[str]) -> list[etree._Element]:
    element = etree.fromstring(item.xml)
    _refuse_unknown_attributes(element, item)
    _refuse_impossible_options(element, item)
    for node in element.iter():
        if isinstance(node.tag, str):
            refuse_reversed_ranges(node, _line_of(node, element, item))
    if item.section in SINGLE_SECTIONS:
        existing = root.find(item.section)
        if existing is None:
            model_section(root, item.section)
            existing = root.find(item.section)
        for key, value in element.attrib.items():
            existing.set(key, value)
        for child in element:
            existing.append(child)
        return [existing, *existing.iter()]
    section = model_section(root, item.section)
    if item.section == "default":
        return _merge_default(section, element, item.origin, warnings)
    section.append(element)
    return list(element.iter())


def _refuse_unknown_attributes(element: etree._Element, item: RawElement) -> None:
    """Refuse, at its line, an attribute that MuJoCo's element of that name has in none of
    its places (MuJoCo would refuse the assembled model without saying which input set it);
    an element MuJoCo does not have is left to MuJoCo's own error."""
    from mjcfbuild.inputs.mujoco_schema import mujoco_attributes_anywhere

    for node in element.iter():
        if not isinstance(node.tag, str):
            continue
        known = mujoco_attributes_anywhere(node.tag)
        # A namespaced attribute ("{uri}name") is no MuJoCo attribute and no typo either.
        unknown = [n for n in node.attrib if known and n not in known and not n.startswith("{")]
        if unknown:
            inside = "" if node is element else f" inside <{element.tag}>"
            raise input_error(
                _line_of(node, element, item),
                f"<{node.tag}>{inside} has no attribute '{unknown[0]}'"
                + did_you_mean(unknown[0], set(known)),
                hint=f"MuJoCo's <{node.tag}> attributes: {_listing(known, limit=len(known))}",
            )


# The timesteps a build simulates with: MuJoCo compiles any value, but the build's trials, its
# check and its tuning report simulate seconds of motion. Below, a build takes hours (1e-9: a
# billion steps a second); above, a 1 s hold is a step or two and proves nothing (a 1 s
# timestep passed the check with a servo swinging outside its range), and a robot's contacts
# and servos do not hold. Menagerie's models use 0.002-0.005 s.
SHORTEST_TIMESTEP = 1e-5
LONGEST_TIMESTEP = 0.05


def _refuse_impossible_options(element: etree._Element, item: RawElement) -> None:
    """Refuse, at its line, an ``<option>`` a build cannot simulate with, which MuJoCo
    compiles all the same: a number that is not finite (gravity="0 0 nan": the check's
    simulation went non-finite and blamed the servos), no solver iterations (nothing holds
    a contact or a joint limit), a timestep outside :data:`SHORTEST_TIMESTEP` to
    :data:`LONGEST_TIMESTEP`."""
    import math

    for node in element.iter("option"):
        for name, text in node.attrib.items():
            if name == "timestep":
                continue  # below, with the timesteps a build simulates with
            words = str(text).split()
            if any(not math.isfinite(number) for number in _numbers(words)):
                raise input_error(
                    _line_of(node, element, item),
                    f'<option {name}="{text}">: every number must be finite',
                )
        if node.get("iterations", "").strip() == "0":
            raise input_error(
                _line_of(node, element, item),
                '<option iterations="0">: with no solver iterations nothing holds a contact, '
                "a joint limit or an equality",
                hint="MuJoCo's default is 100",
            )
        text = node.get("timestep")
        if text is None:
            continue
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not (math.isfinite(value) and value > 0):
            raise input_error(
                _line_of(node, element, item),
                f'<option timestep="{text}">: the timestep must be a positive number of seconds',
                hint="MuJoCo's default is 0.002",
            )
        if not SHORTEST_TIMESTEP <= value <= LONGEST_TIMESTEP:
            raise input_error(
                _line_of(node, element, item),
                f'<option timestep="{text}">: a build simulates with timesteps from '
                f"{SHORTEST_TIMESTEP:g} to {LONGEST_TIMESTEP:g} s",
                hint="MuJoCo's default is 0.002; MuJoCo Menagerie's models use 0.002-0.005",
            )


# Each range attribute and the attribute that says whether it limits anything.
RANGE_LIMITS = {
    "range": "limited",
    "ctrlrange": "ctrllimited",
    "forcerange": "forcelimited",
    "actrange": "actlimited",
    "actuatorfrcrange": "actuatorfrclimited",
}


def refuse_reversed_ranges(node: etree._Element, origin: str) -> None:
    """Refuse, at ``origin``, a range whose lower bound is not below its upper one: MuJoCo
    (autolimits) compiles it as no limit at all, so ``range="3 -3"`` left a joint free to
    turn. ``"0 0"`` is MuJoCo's way to say "no range" and stays allowed, as does any range
    its ``limited`` attribute turns off."""
    for name, limited in RANGE_LIMITS.items():
        text = node.get(name)
        if text is None or node.get(limited, "").strip() == "false":
            continue
        bounds = _numbers(str(text).split())
        if len(bounds) != 2 or bounds == [0.0, 0.0] or bounds[0] < bounds[1]:
            continue
        raise input_error(
            origin,
            f'<{node.tag}{_named(node)} {name}="{text}">: the lower bound must be below the '
            "upper one (MuJoCo would compile it as no limit at all)",
            hint=f'write it as "{_format(bounds[1])} {_format(bounds[0])}"'
            if bounds[0] > bounds[1]
            else f'"0 0" for no limit, or set {limited}="false"',
        )


def _named(node: etree._Element) -> str:
    name = node.get("name")
    return f' name="{name}"' if name else ""


def _format(number: float) -> str:
    return f"{number:g}"


def _numbers(words: list[str]) -> list[float]:
    """The words that are numbers, as numbers (an attribute may hold keywords instead)."""
    numbers = []
    for word in words:
        try:
            numbers.append(float(word))
        except ValueError:
            continue
    return numbers


def _line_of(node: etree._Element, element: etree._Element, item: RawElement) -> str:
    """The origin of ``node``, a descendant of the raw ``element`` (or itself): its own line
    where the raw text kept the input's lines, else the raw element's."""
    file, line = origin_location(item.origin)
    if node is element or line is None or not item.lines_kept:
        return item.origin
    if node.sourceline is None or element.sourceline is None:
        return item.origin
    return f"{file}:{line + node.sourceline - element.sourceline}"


def _merge_default(
    section: etree._Element, element: etree._Element, origin: str, warnings: list[str]
):
    """Merge an input default (a class, or an element of the main class) into the model's."""
    if element.tag != "default":
        target = section.find(element.tag)
        if target is None:
            section.insert(0, element)
            return [element]
        _merge_attributes(target, element, "the main default class", origin, warnings)
        return [target]
    name = element.get("class")
    existing = next((d for d in section.findall("default") if d.get("class") == name), None)
    if existing is None:
        section.append(element)
        return list(element.iter())
    for child in element:
        if child.tag == "default":
            existing.append(child)
            continue
        target = existing.find(child.tag)
        if target is None:
            existing.append(child)
        else:
            _merge_attributes(target, child, f"default class '{name}'", origin, warnings)
    return [existing]


def _merge_attributes(target, source, where: str, origin: str, warnings: list[str]) -> None:
    for key, value in source.attrib.items():
        current = target.get(key)
        if current is not None and current != value:
            warnings.append(
                f"{origin}: {where} sets {source.tag} {key}={value!r} "
                f"(mjcfbuild's is {current!r}); using {value!r}"
            )
        target.set(key, value)


def _modify_targets(
    root: etree._Element, modify: ModifyInput, mesh_aliases: dict[str, set[str]]
) -> list[etree._Element]:
    _refuse_unknown_element_type(root, modify)
    _mujoco_has(
        modify.attributes, modify.type, f"modify_element {modify.describe()}", modify.origin
    )
    if modify.type == "geom":
        return _modified_geoms(root, modify, mesh_aliases)
    candidates = [
        element
        for element in root.iter(modify.type)
        if element.getparent() is not None and element.getparent().tag != "default"
    ]
    found = [element for element in candidates if element.get("name") == modify.name]
    if not found:
        assert modify.name is not None, "ModifyInput names every element but a geom"
        existing = {str(e.get("name")) for e in candidates if e.get("name")}
        raise input_error(
            modify.origin,
            f"modify_element: no {modify.type} named '{modify.name}'"
            f"{did_you_mean(modify.name, existing)}",
            hint=f"{modify.type} names: {_listing(existing)}",
        )
    return found


def _refuse_unknown_element_type(root: etree._Element, modify: ModifyInput) -> None:
    """Refuse a modification whose ``type`` is no MuJoCo element that has a name ('jiont'),
    naming the closest type and the types of the model's named elements."""
    from mjcfbuild.inputs.mujoco_schema import mujoco_named_elements

    known = mujoco_named_elements()
    if modify.type in known:
        return
    present = {
        str(element.tag)
        for element in root.iter()
        if isinstance(element.tag, str) and element.tag in known and element.get("name")
    }
    raise input_error(
        modify.origin,
        f"modify_element: unknown element type '{modify.type}'"
        f"{did_you_mean(modify.type, set(known))}",
        hint=f"element types with names in the model: {_listing(present | {'geom'})}",
    )


def _modified_geoms(
    root: etree._Element, modify: ModifyInput, mesh_aliases: dict[str, set[str]]
) -> list[etree._Element]:
    """The geoms ``modify`` finds by mesh and class; none is an error naming the closest mesh
    (or the classes that mesh's geoms have)."""
    assert modify.mesh is not None and modify.geom_class is not None, "validated by ModifyInput"
    meshes = {name for name, aliases in mesh_aliases.items() if modify.mesh in aliases}
    geoms = [geom for geom in root.find("worldbody").iter("geom") if geom.get("mesh") in meshes]
    found = [geom for geom in geoms if geom.get("class") == modify.geom_class]
    if found:
        return found
    if not meshes:
        aliases = {alias for names in mesh_aliases.values() for alias in names}
        why = f"no mesh is named '{modify.mesh}'{did_you_mean(modify.mesh, aliases)}"
    else:
        classes = {str(geom.get("class")) for geom in geoms if geom.get("class")}
        why = (
            f"the geoms of mesh '{modify.mesh}' have class {_listing(classes)}"
            f"{did_you_mean(modify.geom_class, classes)}"
        )
    raise input_error(
        modify.origin,
        f"modify_element: no {modify.describe()}: {why}",
        hint=f"meshes: {_listing(mesh_aliases)}; classes: visual, collision",
    )


# Attributes that name other elements, and the kind of element they name.
REFERENCES = {
    "joint": "joint",
    "joint1": "joint",
    "joint2": "joint",
    "jointinparent": "joint",
    "body": "body",
    "body1": "body",
    "body2": "body",
    "bodyname": "body",
    "site": "site",
    "site1": "site",
    "site2": "site",
    "cranksite": "site",
    "slidersite": "site",
    "tendon": "tendon",
    "tendon1": "tendon",
    "tendon2": "tendon",
    "geom": "geom",
    "geom1": "geom",
    "geom2": "geom",
    "actuator": "actuator",
    "camera": "camera",
    "mesh": "mesh",
    "material": "material",
    "texture": "texture",
    "class": "class",
    "childclass": "class",
}
OBJECT_TYPES = {
    "body": "body",
    "xbody": "body",
    "geom": "geom",
    "site": "site",
    "camera": "camera",
    "joint": "joint",
    "tendon": "tendon",
    "actuator": "actuator",
}
TENDON_TAGS = ("fixed", "spatial")


def model_names(root: etree._Element) -> dict[str, set[str]]:
    """Names of every kind of element in the model tree."""
    names: dict[str, set[str]] = {kind: set() for kind in set(REFERENCES.values())}
    names["body"].add("world")
    worldbody = root.find("worldbody")
    for kind in ("body", "joint", "site", "geom", "camera"):
        for element in worldbody.iter(kind):
            if element.get("name"):
                names[kind].add(element.get("name"))
    for element in worldbody.iter("freejoint"):
        if element.get("name"):
            names["joint"].add(element.get("name"))
    for asset in root.findall("asset"):
        for kind in ("mesh", "material", "texture"):
            for element in asset.findall(kind):
                if element.get("name"):
                    names[kind].add(element.get("name"))
    for tendon in root.findall("tendon"):
        names["tendon"] |= {e.get("name") for e in tendon if e.tag in TENDON_TAGS and e.get("name")}
    for actuator in root.findall("actuator"):
        names["actuator"] |= {
            e.get("name") for e in actuator if e.tag in ACTUATOR_TAGS and e.get("name")
        }
    names["class"] = {"main"} | {d.get("class") for d in root.iter("default") if d.get("class")}
    return names


def check_references(root: etree._Element, tracked: list[tuple[etree._Element, str]]) -> None:
    """Every name the tracked input elements refer to exists in the model."""
    names = model_names(root)
    for element, origin in tracked:
        if not isinstance(element.tag, str):
            continue
        for attribute, kind in REFERENCES.items():
            value = element.get(attribute)
            if value is None or _declares(element, attribute):
                continue
            if value not in names[kind]:
                raise _missing(element, attribute, value, kind, names, origin)
        objtype, objname = element.get("objtype"), element.get("objname")
        if objtype in OBJECT_TYPES and objname is not None:
            kind = OBJECT_TYPES[objtype]
            if objname not in names[kind]:
                raise _missing(element, "objname", objname, kind, names, origin)


def _declares(element: etree._Element, attribute: str) -> bool:
    """Whether the attribute declares a name rather than referring to one."""
    parent = element.getparent()
    if attribute == "class" and element.tag == "default":
        return True
    # <joint joint="..."> inside a fixed tendon refers; <geom mesh> refers; nothing else here
    # declares a name through these attributes, except asset elements naming their files.
    return parent is not None and parent.tag == "default"


def _missing(element, attribute, value, kind, names, origin) -> InputError:
    what = f"<{element.tag}{' ' + repr(element.get('name')) if element.get('name') else ''}>"
    return input_error(
        origin,
        f'{what} {attribute}="{value}" names a {kind} that does not exist'
        f"{did_you_mean(value, set(names[kind]))}",
        hint=f"{kind} names: {_listing(names[kind])}",
    )
