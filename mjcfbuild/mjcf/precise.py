"""Writing an MjSpec as MJCF without MuJoCo's 6-digit rounding.

``MjSpec.to_xml()`` prints numbers with 6 significant digits (``0.707105`` for a quaternion),
so a converted chain drifts from its URDF by about 1e-6. It also compiles the model first and
writes back compiled values (a mesh geom's identity pose comes out as ``pos="2.7e-16 ..."``).

This module takes a snapshot of the spec's own values before ``to_xml()``, gives every element
a name so it can be found in the XML again, and writes the snapshot back at 12 digits. A value
is only replaced where the XML shows the same number rounded, so an element is never given
numbers that belong to another.
"""

from __future__ import annotations

import math

from lxml import etree

from mjcfbuild.numbers import output_list

# XML attribute -> spec field, per element kind.
FIELDS: dict[str, dict[str, str]] = {
    "body": {"pos": "pos", "quat": "quat"},
    "inertial": {
        "pos": "ipos",
        "quat": "iquat",
        "mass": "mass",
        "diaginertia": "inertia",
        "fullinertia": "fullinertia",
    },
    "joint": {
        "pos": "pos",
        "axis": "axis",
        "range": "range",
        "ref": "ref",
        "springref": "springref",
        "armature": "armature",
        "damping": "damping",
        "frictionloss": "frictionloss",
        "stiffness": "stiffness",
        "actuatorfrcrange": "actfrcrange",
    },
    "geom": {"pos": "pos", "quat": "quat", "size": "size", "fromto": "fromto"},
    "site": {"pos": "pos", "quat": "quat", "size": "size"},
    "camera": {"pos": "pos", "quat": "quat", "fovy": "fovy"},
    "mesh": {"scale": "scale"},
    "frame": {"pos": "pos", "quat": "quat"},
}
DEFAULTS = {"pos": (0.0, 0.0, 0.0), "quat": (1.0, 0.0, 0.0, 0.0)}
_COLLECTIONS = {
    "body": "bodies",
    "joint": "joints",
    "geom": "geoms",
    "site": "sites",
    "camera": "cameras",
    "mesh": "meshes",
    "frame": "frames",
}
_TEMP_PREFIX = "mjcfbuild_unnamed_"
# Poses and directions: values below this are rounding noise of rotations (1e-22 and the like).
_GEOMETRIC = {"pos", "quat", "axis"}
_NOISE = 1e-14
# Below this fraction of its array's largest number, MuJoCo's writer prints a number as 0.
_RELATIVE_ZERO = 1e-6


def precise_xml(spec) -> etree._Element:
    """The spec as an lxml tree, every number taken from the spec at 12 digits."""
    temporary = _name_unnamed(spec)
    try:
        snapshot = _snapshot(spec)
        text = spec.to_xml()
    finally:
        for element in temporary:
            element.name = ""
    # huge_tree: libxml2 stops at 256 nested elements otherwise; chains nest bodies deeper.
    root = etree.fromstring(text.encode("utf-8"), etree.XMLParser(huge_tree=True))
    for container in [*root.iter("worldbody"), *root.iter("asset")]:
        for element in container.iter(*FIELDS):
            name = element.get("name")
            if element.tag == "inertial":
                parent = element.getparent()
                values = snapshot.get(("inertial", parent.get("name")))
            else:
                values = snapshot.get((element.tag, name))
            if values is not None:
                _patch(element, values)
            if name is not None and name.startswith(_TEMP_PREFIX):
                del element.attrib["name"]
    return root


def _name_unnamed(spec) -> list:
    named = []
    for kind in ("geoms", "sites", "cameras", "bodies", "joints", "frames"):
        for index, element in enumerate(getattr(spec, kind)):
            if not element.name and not (kind == "bodies" and element == spec.worldbody):
                element.name = f"{_TEMP_PREFIX}{kind}_{index}"
                named.append(element)
    return named


def _snapshot(spec) -> dict[tuple[str, str], dict[str, tuple[float, ...]]]:
    snapshot: dict[tuple[str, str], dict[str, tuple[float, ...]]] = {}
    for tag, collection in _COLLECTIONS.items():
        for element in getattr(spec, collection):
            snapshot[(tag, element.name)] = _values(element, FIELDS[tag])
            if tag == "body":
                snapshot[("inertial", element.name)] = _values(element, FIELDS["inertial"])
    return snapshot


def _values(element, fields: dict[str, str]) -> dict[str, tuple[float, ...]]:
    result = {}
    for attribute, field in fields.items():
        value = getattr(element, field, None)
        if value is None:
            continue
        try:
            numbers = tuple(float(v) for v in (value if hasattr(value, "__len__") else [value]))
        except (TypeError, ValueError):
            continue
        result[attribute] = numbers
    return result


def _patch(element: etree._Element, values: dict[str, tuple[float, ...]]) -> None:
    for attribute, given in values.items():
        text = element.get(attribute)
        if text is None:
            continue
        try:
            shown = [float(t) for t in text.split()]
        except ValueError:
            continue
        # MuJoCo writes an axis as a unit one (0.136083 0.272166 0.952579 for 1 2 7).
        candidates = [given, _unit(given)] if attribute == "axis" else [given]
        exact = next((c for c in candidates if _shows(shown, c)), None)
        if exact is None:
            continue
        new = exact[: len(shown)]
        if attribute in _GEOMETRIC:
            new = tuple(0.0 if abs(v) < _NOISE else v for v in new)
        if (
            attribute in DEFAULTS
            and element.tag != "inertial"
            and _is_default(new, DEFAULTS[attribute])
        ):
            del element.attrib[attribute]
        else:
            element.set(attribute, output_list(new))


def _shows(shown: list[float], exact: tuple[float, ...]) -> bool:
    """Whether the numbers ``shown`` are ``exact``'s, as MuJoCo's writer rounds them."""
    scale = max((abs(v) for v in exact[: len(shown)]), default=0.0)
    return len(shown) <= len(exact) and all(
        math.isfinite(v) and _same_when_rounded(s, v, scale)
        for s, v in zip(shown, exact, strict=False)
    )


def _unit(values: tuple[float, ...]) -> tuple[float, ...]:
    """``values`` scaled to length 1 (as they are where they have none)."""
    length = math.sqrt(sum(v * v for v in values))
    return tuple(v / length for v in values) if length > 0 else values


def _same_when_rounded(shown: float, exact: float, scale: float) -> bool:
    """Whether ``shown`` is ``exact`` printed with 6 significant digits (or tiny noise).

    MuJoCo's writer prints a number that is tiny next to the largest of its array as 0 (a
    cylinder's radius 0.01 beside a half-length of 1.25e11 came out as ``size="0 1.25e+11"``,
    which MuJoCo then refuses to load); that 0 is ``exact`` too.
    """
    if shown == 0.0 and abs(exact) <= _RELATIVE_ZERO * scale:
        return True
    return abs(shown - exact) <= 1e-5 * max(abs(exact), 1e-9) + 1e-12


def _is_default(values: tuple[float, ...], default: tuple[float, ...]) -> bool:
    return len(values) == len(default) and all(
        abs(a - b) < 1e-15 for a, b in zip(values, default, strict=True)
    )
