"""Parsing URDF bytes into a :class:`Robot`, with errors that name the file and line.

The XML is parsed as bytes (real files declare their encoding), with entity expansion and
network access off. Three defects seen in real descriptions are repaired with a warning
instead of failing: undeclared namespace prefixes (``drake:...``; the prefixed elements are
ignored), numbers separated by commas (``rpy="1.57, 0, 0"``), and what MuJoCo's own URDF
import and pybullet read although XML forbids it: an XML declaration after blank lines or
with a version other than 1.0, and NUL bytes after the root element (pybullet_data's
``biped2d_pybullet.urdf``, ``bike.urdf`` and ``humanoid.urdf``). A joint whose parent is a
``world`` link the URDF never declares is welded to the ground, as Drake reads it.
"""

from __future__ import annotations

import math
import re
from typing import Literal, NoReturn, overload

from lxml import etree

from mjcfbuild.errors import InputError, first_at
from mjcfbuild.sources.packages import did_you_mean
from mjcfbuild.urdf.model import (
    JOINT_TYPES,
    RGBA,
    WORLD,
    Geometry,
    Inertial,
    Joint,
    Limit,
    Link,
    Material,
    Mimic,
    Pose,
    Robot,
    Shape,
    Vec3,
)
from mjcfbuild.urdf.transforms import vec3
from mjcfbuild.xmlguard import blank_inert, refuse_entities

_SEPARATORS = re.compile(r"[\s,]+")
# A number as C's strtod reads it in the C locale, which urdfdom (ROS's URDF parser) requires:
# Python's float() also takes digits of other scripts ("١") and underscores ("1_000").
_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NUMBER_HINT = "write it with the digits 0-9, as ROS's URDF parser (urdfdom) requires"


def secure_parser(recover: bool = False, keep_comments: bool = False) -> etree.XMLParser:
    """An lxml parser that expands no entities, loads no DTD and touches no network; it drops
    comments and processing instructions unless ``keep_comments``."""
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        huge_tree=False,
        remove_comments=not keep_comments,
        remove_pis=not keep_comments,
        recover=recover,
    )


def parse_xml(
    data: bytes, display_file: str, warnings: list[str], keep_comments: bool = False
) -> etree._Element:
    """Parse XML bytes safely, as MuJoCo's and urdfdom's parser (tinyxml2) reads them where
    libxml2 would refuse them, each such reading a warning; undeclared namespace prefixes are a
    warning, the rest errors. Comments and processing instructions are dropped unless
    ``keep_comments``."""
    if not data.strip():
        raise InputError("the file is empty", file=display_file)
    refuse_entities(data, display_file)
    data = _repair_declaration(data, display_file, warnings)
    data = _drop_trailing_nuls(data, display_file, warnings)
    _warn_late_instruction(data, display_file, warnings)
    return _parse_as_tinyxml2_reads(data, display_file, warnings, keep_comments)


def _parse_as_tinyxml2_reads(
    data: bytes, display_file: str, warnings: list[str], keep_comments: bool
) -> etree._Element:
    """Parse ``data``; where libxml2 stops at what tinyxml2 reads past (content after the
    root's end, bytes that are not UTF-8), read it as tinyxml2 does, with a warning."""
    try:
        return etree.fromstring(data, secure_parser(keep_comments=keep_comments))
    except etree.XMLSyntaxError as exc:
        after_root = _stray_closing_tag(data, exc) or _second_root(data, exc)
        if after_root is not None:
            what, offset = after_root
            warnings.append(
                f"{display_file}:{exc.lineno}: {what} after the root element's end; ignored "
                "with what follows it, as MuJoCo's and urdfdom's parser (tinyxml2) read the "
                "first root element only (remove it)"
            )
            return _parse_as_tinyxml2_reads(data[:offset], display_file, warnings, keep_comments)
        if exc.code == _INVALID_ENCODING and not _is_utf8(data) and _says_utf8(data):
            latin1 = _latin1_bytes(data, display_file, warnings)
            return _parse_as_tinyxml2_reads(latin1, display_file, warnings, keep_comments)
        if exc.code != 201:  # 201: namespace prefix not defined
            raise InputError(
                f"malformed XML: {_clean_xml_message(exc.msg)}",
                file=display_file,
                line=exc.lineno,
                column=exc.position[1] if exc.position else None,
            ) from None
    parser = secure_parser(recover=True, keep_comments=keep_comments)
    root = etree.fromstring(data, parser)
    real_errors = [e for e in parser.error_log if e.domain_name != "NAMESPACE"]
    if root is None or real_errors:
        first = real_errors[0] if real_errors else None
        raise InputError(
            f"malformed XML: {first.message if first else 'unreadable'}",
            file=display_file,
            line=first.line if first else None,
        )
    prefixes = sorted(
        {m.group(1) for e in parser.error_log for m in [_PREFIX.search(e.message)] if m}
    )
    warnings.append(
        f"{display_file}: undeclared XML namespace prefix(es) {', '.join(prefixes) or '?'}; "
        "elements using them are ignored"
    )
    return root


_PREFIX = re.compile(r"Namespace prefix (\S+)")
# An XML declaration after leading white space (XML allows nothing before it), and its version.
_DECLARATION = re.compile(rb"\A(\s*)(<\?xml\s[^>]*?\?>)")
_VERSION = re.compile(rb"""(\sversion\s*=\s*)(["'])([^"']*)\2""")
_ENCODING = re.compile(rb"""(\sencoding\s*=\s*)(["'])([^"']*)\2""")


def _repair_declaration(data: bytes, display_file: str, warnings: list[str]) -> bytes:
    """``data`` with its XML declaration moved to the very start and its version made 1.0,
    each with a warning; every element stays on its line (the blank lines follow the
    declaration instead of preceding it)."""
    found = _DECLARATION.match(data)
    if found is None:
        return data
    space, declaration = found.group(1), found.group(2)
    line = space.count(b"\n") + 1
    version = _VERSION.search(declaration)
    if version is not None and not version.group(3).startswith(b"1."):
        written = version.group(3).decode("ascii", "replace")
        start, end = version.span(3)
        declaration = declaration[:start] + b"1.0" + declaration[end:]
        warnings.append(
            f"{display_file}:{line}: the XML declaration "
            f'says version "{written}"; read as 1.0 (write version="1.0")'
        )
    encoding = _ENCODING.search(declaration)
    named = encoding.group(3).decode("ascii", "replace") if encoding else "UTF-8"
    if named.replace("-", "").lower() != "utf8" and not data.isascii() and _is_utf8(data):
        # ROS's parser (urdfdom) and MuJoCo's read every file as UTF-8, whatever the
        # declaration says: names with accents came out differently (or not at all) here.
        assert encoding is not None
        start, end = encoding.span(3)
        declaration = declaration[:start] + b"UTF-8" + declaration[end:]
        warnings.append(
            f'{display_file}:{line}: the XML declaration says encoding="{named}" but the file '
            "is UTF-8; read as UTF-8, as ROS's and MuJoCo's URDF parsers read it (write "
            'encoding="UTF-8")'
        )
    problem = _declaration_problem(declaration)
    if problem is not None:
        # tinyxml2 (MuJoCo's and urdfdom's parser) skips a declaration without reading it.
        warnings.append(
            f"{display_file}:{line}: the XML declaration is malformed ({problem}); read "
            "without it, as MuJoCo's and ROS's URDF parsers read the file (write "
            '<?xml version="1.0"?>)'
        )
        declaration = b'<?xml version="1.0"?>'
    if space:
        warnings.append(
            f"{display_file}:{line}: the XML declaration follows blank "
            "lines; read as if it came first (remove what precedes it)"
        )
    return declaration + space + data[found.end() :]


def _declaration_problem(declaration: bytes) -> str | None:
    """What libxml2 finds wrong with an XML ``declaration`` (``verison="1.0"``); None where
    it reads it."""
    try:
        etree.fromstring(declaration + b"<r/>", secure_parser())
    except etree.XMLSyntaxError as exc:
        return _clean_xml_message(exc.msg)
    return None


_LEADING_INSTRUCTIONS = re.compile(rb"(?:\s*<\?.*?\?>)*", re.DOTALL)


def _warn_late_instruction(data: bytes, display_file: str, warnings: list[str]) -> None:
    """A warning at the first ``<?...?>`` after the file's first node that is not one: libxml2
    reads the file without it, tinyxml2 (MuJoCo's and urdfdom's parser) refuses the file
    ("XML_ERROR_PARSING_DECLARATION"), since it takes every ``<?`` for a declaration, which
    only the start of a file may hold."""
    body = data.removeprefix(b"\xef\xbb\xbf")
    start = _LEADING_INSTRUCTIONS.match(body)
    begin = start.end() if start is not None else 0
    blanked = blank_inert(body[begin:])
    found = blanked.find(b"<?")
    if found < 0:
        return
    offset = len(data) - len(body) + begin + found
    name = re.match(rb"<\?([^\s?>]*)", data[offset:])
    tag = name.group(1).decode("utf-8", "replace") if name else ""
    if tag.lower() == "xml":
        return  # a late XML declaration: libxml2 refuses it too, in one error
    line = data.count(b"\n", 0, offset) + 1
    warnings.append(
        f"{display_file}:{line}: <?{tag} ...?> after the start of "
        "the file is read without it here, but MuJoCo's and urdfdom's parser (tinyxml2) refuse "
        "the file there (remove it, or move it before everything else)"
    )


def _is_utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


def _drop_trailing_nuls(data: bytes, display_file: str, warnings: list[str]) -> bytes:
    """``data`` without the NUL bytes (and white space) at its end, with a warning: a C
    string's terminator written into the file, which C parsers never see."""
    kept = data.rstrip(b"\x00 \t\r\n")
    if b"\x00" not in data[len(kept) :] or b"\x00" in kept:
        return data  # none, or NULs all through: UTF-16 or UTF-32, whose characters hold them
    line = data[: data.index(b"\x00", len(kept))].count(b"\n") + 1
    warnings.append(
        f"{display_file}:{line}: NUL bytes after the end of the XML; ignored (remove them)"
    )
    return kept + b"\n"


# A closing tag as tinyxml2 reads one: a name right after "</", then anything up to ">".
_CLOSING_TAG = re.compile(rb"</[A-Za-z_:][^\s>/]*(?:\s[^>]*)?>")


def _stray_closing_tag(data: bytes, exc: etree.XMLSyntaxError) -> tuple[str, int] | None:
    """(what it is, its offset in ``data``) where ``exc`` is about a closing tag after the root
    element's end (PyFlyt's rocket.urdf ends ``</robot>`` twice). tinyxml2, MuJoCo's and
    urdfdom's parser, ends the document there and reads the model; other content after the
    root (text, an unclosed element) it refuses as lxml does, so only this is taken."""
    if exc.code != 5 or not exc.position or exc.lineno is None:  # 5: extra content at end
        return None
    offset = _offset(data, *exc.position)
    found = _CLOSING_TAG.match(data, offset) if offset is not None else None
    if offset is None or found is None or not data[:offset].strip():
        return None
    return f"a closing tag {found.group().decode('utf-8', 'replace')}", offset


# A start tag as tinyxml2 reads one: "<" and a name.
_OPENING_TAG = re.compile(rb"<([A-Za-z_:][^\s>/]*)")


def _second_root(data: bytes, exc: etree.XMLSyntaxError) -> tuple[str, int] | None:
    """(what it is, its offset in ``data``) where ``exc`` is about a second root element after
    the first one's end. tinyxml2 reads every top-level element of a well-formed sequence and
    MuJoCo's and urdfdom's importers take the first; what follows the first root refused
    there (text, an unclosed element) stays an error here."""
    if exc.code != 5 or not exc.position or exc.lineno is None:  # 5: extra content at end
        return None
    offset = _offset(data, *exc.position)
    found = _OPENING_TAG.match(data, offset) if offset is not None else None
    if offset is None or found is None or not data[:offset].strip():
        return None
    try:  # the rest as tinyxml2 reads it: elements, comments and white space, well formed
        rest = etree.fromstring(b"<rest>" + data[offset:] + b"</rest>", secure_parser())
    except etree.XMLSyntaxError:
        return None
    if (rest.text or "").strip() or any((child.tail or "").strip() for child in rest):
        return None
    return f"a second root element <{found.group(1).decode('utf-8', 'replace')}>", offset


def _offset(data: bytes, line: int, column: int) -> int | None:
    """The byte offset of libxml2's ``line`` and ``column`` (counted in characters; the file
    is UTF-8, or ASCII, where it matters)."""
    lines = data.split(b"\n")
    if not 0 < line <= len(lines) or column < 1:
        return None
    start = sum(len(text) + 1 for text in lines[: line - 1])
    return start + len(lines[line - 1].decode("utf-8", "replace")[: column - 1].encode("utf-8"))


_INVALID_ENCODING = 81  # libxml2: "Invalid bytes in character encoding"


def _says_utf8(data: bytes) -> bool:
    """Whether ``data``'s XML declaration names UTF-8 or no encoding (XML's default)."""
    found = _DECLARATION.match(data.removeprefix(b"\xef\xbb\xbf"))
    encoding = _ENCODING.search(found.group(2)) if found is not None else None
    return encoding is None or encoding.group(3).replace(b"-", b"").lower() == b"utf8"


def _latin1_bytes(data: bytes, display_file: str, warnings: list[str]) -> bytes:
    """``data`` with each byte that is not UTF-8 read as Latin-1 (0xE9: 'é'), with a warning
    at the first: tinyxml2, MuJoCo's and urdfdom's parser, takes bytes as they are and reads
    the file, where libxml2 refuses it."""
    text = data.decode("utf-8", "surrogateescape")
    first = next(i for i, c in enumerate(text) if "\udc80" <= c <= "\udcff")
    count = sum("\udc80" <= c <= "\udcff" for c in text)
    byte = ord(text[first]) - 0xDC00
    more = f" (and {count - 1} more)" if count > 1 else ""
    # 0x80-0x9f are control characters in Latin-1 (Windows-1252's quotes): named, not printed.
    shown = f"'{chr(byte)}'" if chr(byte).isprintable() else f"U+{byte:04X}"
    warnings.append(
        f"{display_file}:{text.count(chr(10), 0, first) + 1}: byte 0x{byte:02x} is not UTF-8"
        f"{more}; read as Latin-1 ({shown}), as MuJoCo's and urdfdom's parser (tinyxml2) "
        "read the file without a word (save it as UTF-8)"
    )
    fixed = "".join(chr(ord(c) - 0xDC00) if "\udc80" <= c <= "\udcff" else c for c in text)
    return fixed.encode("utf-8")


def _clean_xml_message(message: str) -> str:
    return re.sub(r",? line \d+, column \d+.*$", "", message).strip()


class _Reader:
    """Reads typed values from elements, raising errors that point at the element's line."""

    def __init__(self, display_file: str, warnings: list[str]) -> None:
        self.file = display_file
        self.warnings = warnings

    def error(
        self, element: etree._Element | None, message: str, hint: str | None = None
    ) -> InputError:
        line = element.sourceline if element is not None else None
        return InputError(message, file=self.file, line=line, hint=hint)

    def required(self, element: etree._Element, attribute: str) -> str:
        value = element.get(attribute)
        if value is None or not value.strip():
            raise self.error(element, f"<{element.tag}> needs a '{attribute}' attribute")
        return value.strip()

    # The overloads say what a fixed count gives: `count` numbers, or `default` when the
    # attribute is absent.
    @overload
    def numbers(
        self, element: etree._Element, attribute: str, count: Literal[3], default: Vec3
    ) -> Vec3: ...
    @overload
    def numbers(
        self, element: etree._Element, attribute: str, count: Literal[4], default: None = None
    ) -> RGBA | None: ...
    @overload
    def numbers(
        self, element: etree._Element, attribute: str, count: int | None, default: tuple[float, ...]
    ) -> tuple[float, ...]: ...
    @overload
    def numbers(
        self, element: etree._Element, attribute: str, count: int | None, default: None = None
    ) -> tuple[float, ...] | None: ...
    def numbers(
        self,
        element: etree._Element,
        attribute: str,
        count: int | None,
        default: tuple[float, ...] | None = None,
    ) -> tuple[float, ...] | None:
        text = element.get(attribute)
        if text is None:
            return default
        stripped = text.strip()
        if "," in stripped:
            self.warnings.append(
                f'{self.file}:{element.sourceline}: <{element.tag} {attribute}="{text}"> '
                "uses commas between numbers; read them as spaces"
            )
        parts = [p for p in _SEPARATORS.split(stripped) if p]
        if count is not None and len(parts) != count:
            raise self.error(
                element,
                f'<{element.tag}> {attribute}="{text}" needs {count} number'
                f"{'s' if count > 1 else ''}, found {len(parts)}",
            )
        values = []
        for part in parts:
            try:
                value = float(part)
            except ValueError:
                value = None
            if value is None or (_NUMBER.fullmatch(part) is None and math.isfinite(value)):
                raise self.error(
                    element,
                    f"<{element.tag}> {attribute}=\"{text}\": '{part}' is not a number",
                    hint=_NUMBER_HINT if value is not None else None,
                )
            if not math.isfinite(value):
                raise self.error(
                    element, f'<{element.tag}> {attribute}="{text}" is not a finite number'
                )
            values.append(value)
        return tuple(values)

    @overload
    def number(self, element: etree._Element, attribute: str, default: float) -> float: ...
    @overload
    def number(
        self, element: etree._Element, attribute: str, default: None = None
    ) -> float | None: ...
    def number(
        self, element: etree._Element, attribute: str, default: float | None = None
    ) -> float | None:
        values = self.numbers(element, attribute, 1)
        return default if values is None else values[0]

    def pose(self, parent: etree._Element) -> Pose:
        origin = parent.find("origin")
        if origin is None:
            return Pose()
        return Pose(
            self.numbers(origin, "xyz", 3, (0.0, 0.0, 0.0)),
            self.numbers(origin, "rpy", 3, (0.0, 0.0, 0.0)),
        )


def parse_urdf(data: bytes, display_file: str = "robot.urdf") -> Robot:
    """Parse URDF bytes; :class:`InputError` with file and line for anything malformed."""
    warnings: list[str] = []
    root = parse_xml(data, display_file, warnings)
    reader = _Reader(display_file, warnings)
    if root.tag != "robot":
        raise reader.error(root, f"the root element is <{root.tag}>, a URDF's is <robot>")
    materials = _global_materials(root, reader)
    links = [_parse_link(element, reader, materials) for element in root.findall("link")]
    joints = [_parse_joint(element, reader) for element in root.findall("joint")]
    links = _implicit_world(links, joints, reader)
    robot = Robot(
        name=(root.get("name") or "robot").strip() or "robot",
        links=links,
        joints=joints,
        source=display_file,
        mujoco_compiler=_mujoco_compiler(root, reader),
        warnings=warnings,
    )
    validate_structure(robot, root, reader)
    return robot


def _global_materials(root: etree._Element, reader: _Reader) -> dict[str, Material]:
    result = {}
    for element in root.findall("material"):
        name = reader.required(element, "name")
        result[name] = _material(element, reader, {})
    return result


def _material(element: etree._Element, reader: _Reader, known: dict[str, Material]) -> Material:
    name = element.get("name")
    color = element.find("color")
    texture = element.find("texture")
    rgba = reader.numbers(color, "rgba", 4) if color is not None else None
    texture_file = texture.get("filename") if texture is not None else None
    if rgba is None and texture_file is None and name in known:
        return known[name]
    line = texture.sourceline if texture is not None and texture_file is not None else None
    return Material(name=name, rgba=rgba, texture=texture_file, texture_line=line)


def _parse_link(element: etree._Element, reader: _Reader, materials: dict[str, Material]) -> Link:
    name = reader.required(element, "name")
    _warn_repeated(element, ("inertial",), f"link '{name}'", reader)
    inertial = None
    inertial_element = element.find("inertial")
    if inertial_element is not None:
        inertial = _parse_inertial(inertial_element, reader)
    visuals = [
        _parse_shape(e, "visual", i, reader, materials)
        for i, e in enumerate(element.findall("visual"))
    ]
    collisions = [
        _parse_shape(e, "collision", i, reader, materials)
        for i, e in enumerate(element.findall("collision"))
    ]
    return Link(name, inertial, visuals, collisions, element.sourceline)


def _parse_inertial(element: etree._Element, reader: _Reader) -> Inertial:
    _warn_repeated(element, ("origin", "mass", "inertia"), "<inertial>", reader)
    mass_element = element.find("mass")
    mass = reader.number(mass_element, "value") if mass_element is not None else None
    if mass is None:
        raise reader.error(element, "<inertial> needs <mass value=...>")
    inertia_element = element.find("inertia")
    if inertia_element is None:
        raise reader.error(element, "<inertial> needs <inertia ixx=... iyy=... izz=.../>")
    ixx, ixy, ixz, iyy, iyz, izz = (
        reader.number(inertia_element, key, 0.0)
        for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    )
    inertia = (ixx, ixy, ixz, iyy, iyz, izz)
    return Inertial(reader.pose(element), mass, inertia, element.sourceline)


def _parse_shape(
    element: etree._Element,
    role: str,
    index: int,
    reader: _Reader,
    materials: dict[str, Material],
) -> Shape:
    _warn_repeated(element, ("origin", "geometry", "material"), f"<{role}>", reader)
    geometry_element = element.find("geometry")
    if geometry_element is None or len(geometry_element) == 0:
        raise reader.error(element, f"<{role}> has no <geometry>")
    if len(geometry_element) > 1:
        reader.warnings.append(
            f"{reader.file}:{geometry_element[1].sourceline}: <geometry> holds "
            f"{len(geometry_element)} shapes: only the first, <{geometry_element[0].tag}> "
            f"(line {geometry_element[0].sourceline}), is read, as ROS's URDF parser reads it "
            "(MuJoCo's own import takes a box first, whatever the order); give each shape a "
            "<visual> or <collision> of its own"
        )
    geometry = _parse_geometry(geometry_element[0], reader)
    geometry.line = geometry_element[0].sourceline
    material = None
    material_element = element.find("material")
    if role == "visual" and material_element is not None:
        material = _material(material_element, reader, materials)
    name = element.get("name")
    return Shape(
        role=role,
        index=index,
        origin=reader.pose(element),
        geometry=geometry,
        name=name.strip() if name and name.strip() else None,
        material=material,
        line=element.sourceline,
    )


def _parse_geometry(element: etree._Element, reader: _Reader) -> Geometry:
    kind = element.tag
    if kind == "box":
        return Geometry(
            "box", reader.numbers(element, "size", 3) or _missing(reader, element, "size")
        )
    if kind in ("cylinder", "capsule"):
        radius = reader.number(element, "radius")
        length = reader.number(element, "length")
        if radius is None or length is None:
            raise reader.error(element, f"<{kind}> needs 'radius' and 'length'")
        return Geometry(kind, (radius, length))
    if kind == "sphere":
        radius = reader.number(element, "radius")
        if radius is None:
            raise reader.error(element, "<sphere> needs 'radius'")
        return Geometry("sphere", (radius,))
    if kind == "mesh":
        uri = reader.required(element, "filename")
        scale = reader.numbers(element, "scale", None, (1.0, 1.0, 1.0))
        if len(scale) == 1:
            scale = (scale[0],) * 3
        if len(scale) != 3:
            raise reader.error(element, "<mesh> scale needs 1 or 3 numbers")
        return Geometry("mesh", uri=uri, scale=vec3(scale))
    raise reader.error(
        element,
        f"unknown geometry <{kind}>",
        hint="URDF geometry is one of box, cylinder, sphere, mesh (and capsule)",
    )


def _missing(reader: _Reader, element: etree._Element, attribute: str) -> NoReturn:
    raise reader.error(element, f"<{element.tag}> needs a '{attribute}' attribute")


# pybullet's and MuJoCo's URDF readers take a ball joint (pybullet_data's humanoid.urdf).
_SPHERICAL = (
    "; 'spherical' is pybullet's extension, not URDF: write the ball joint as three revolute "
    "joints through two small links"
)


def _parse_joint(element: etree._Element, reader: _Reader) -> Joint:
    name = reader.required(element, "name")
    kind = reader.required(element, "type")
    if kind not in JOINT_TYPES:
        raise reader.error(
            element,
            f"joint '{name}' has unknown type '{kind}'"
            + ("" if kind == "spherical" else did_you_mean(kind, list(JOINT_TYPES))),
            hint=f"use one of {', '.join(JOINT_TYPES)}"
            + (_SPHERICAL if kind == "spherical" else ""),
        )
    _warn_repeated(element, _JOINT_SINGLES, f"joint '{name}'", reader)
    parent = element.find("parent")
    child = element.find("child")
    if parent is None or child is None:
        raise reader.error(element, f"joint '{name}' needs <parent link=...> and <child link=...>")
    axis = _axis(element.find("axis"), name, kind, reader)
    limit = None
    limit_element = element.find("limit")
    if limit_element is None and kind in ("revolute", "prismatic"):
        reader.warnings.append(
            f"{reader.file}:{element.sourceline}: joint '{name}' is {kind} without <limit>: "
            "ROS's URDF parser (urdfdom) refuses it, MuJoCo's import makes it unlimited; "
            'add <limit lower= upper= effort= velocity=/>, or make it type="continuous"'
            + (" (a prismatic joint cannot be)" if kind == "prismatic" else "")
        )
    if limit_element is not None:
        limit = Limit(
            reader.number(limit_element, "lower"),
            reader.number(limit_element, "upper"),
            reader.number(limit_element, "effort"),
            reader.number(limit_element, "velocity"),
        )
        _check_bounds(name, kind, limit, limit_element, reader)
    damping = friction = 0.0
    dynamics = element.find("dynamics")
    if dynamics is not None:
        damping = reader.number(dynamics, "damping", 0.0)
        friction = reader.number(dynamics, "friction", 0.0)
    mimic = None
    mimic_element = element.find("mimic")
    if mimic_element is not None:
        mimic = Mimic(
            reader.required(mimic_element, "joint"),
            reader.number(mimic_element, "multiplier", 1.0),
            reader.number(mimic_element, "offset", 0.0),
        )
    return Joint(
        name=name,
        kind=kind,
        parent=reader.required(parent, "link"),
        child=reader.required(child, "link"),
        origin=reader.pose(element),
        axis=axis,
        limit=limit,
        damping=damping,
        friction=friction,
        mimic=mimic,
        line=element.sourceline,
    )


_JOINT_SINGLES = (
    "parent", "child", "origin", "axis", "limit", "dynamics", "mimic", "calibration",
    "safety_controller",
)  # fmt: skip


def _warn_repeated(
    element: etree._Element, tags: tuple[str, ...], subject: str, reader: _Reader
) -> None:
    """A warning for each of ``tags`` that ``element`` holds more than once: URDF allows one,
    ROS's URDF parser (urdfdom) reads the first without a word and MuJoCo's own import refuses
    the file ("repeated element"); mjcfbuild reads it as the runtime's parser does."""
    for tag in tags:
        found = element.findall(tag)
        if len(found) > 1:
            reader.warnings.append(
                f"{reader.file}:{found[1].sourceline}: {subject} has {len(found)} <{tag}> "
                f"elements: only the first (line {found[0].sourceline}) is read, as ROS's URDF "
                "parser reads it (MuJoCo's own import refuses the file); remove the others"
            )


def _implicit_world(links: list[Link], joints: list[Joint], reader: _Reader) -> list[Link]:
    """``links``, with an empty ``world`` link first when a joint's parent is a ``world`` the
    URDF does not declare: Drake reads that link as the ground (drake's
    ``Acrobot.urdf`` welds its base to it), ROS's urdfdom refuses it, so it comes with a
    warning."""
    if any(link.name == WORLD for link in links):
        return links
    welded = [joint for joint in joints if joint.parent == WORLD]
    if not welded:
        return links
    reader.warnings.append(
        f"{reader.file}:{welded[0].line}: joint '{welded[0].name}' has the parent link "
        f"'{WORLD}', which the URDF does not declare: taken as the ground, as Drake reads "
        f'it (add <link name="{WORLD}"/> for the readers that refuse it: ROS\'s urdfdom, '
        "MuJoCo's own import)"
    )
    return [Link(WORLD), *links]


def _check_bounds(
    joint: str, kind: str, limit: Limit, element: etree._Element, reader: _Reader
) -> None:
    """Refuse a revolute or prismatic joint whose lower bound lies above its upper one, a
    missing bound being 0 as in the URDF specification (and urdfdom): MuJoCo would leave such
    a joint unlimited."""
    if kind not in ("revolute", "prismatic") or (limit.lower is None and limit.upper is None):
        return
    lower, upper = limit.lower or 0.0, limit.upper or 0.0
    if lower <= upper:
        return
    message = f"joint '{joint}' has lower limit {lower:g} above its upper limit {upper:g}"
    if limit.lower is None or limit.upper is None:
        missing = "lower" if limit.lower is None else "upper"
        raise reader.error(
            element,
            f"{message} (it gives no {missing}, which URDF reads as 0)",
            hint=f"give the {missing} limit too",
        )
    raise reader.error(
        element,
        message,
        # pybullet_data's biped2d_pybullet.urdf writes lower 1, upper -1 for "free".
        hint="swap them; if they mean 'no limit' (as pybullet reads them), make a "
        "revolute joint continuous, or give a prismatic one the range it can travel",
    )


def _axis(element: etree._Element | None, joint: str, kind: str, reader: _Reader) -> Vec3:
    """The joint's axis (x where none is given). A fixed or floating joint has no axis: ROS's
    URDF parser does not read one there, and mjcfbuild only warns when it cannot either."""
    axis = (1.0, 0.0, 0.0)
    if element is None:
        return axis
    if kind in ("fixed", "floating"):
        try:
            return reader.numbers(element, "xyz", 3, axis)
        except InputError as error:
            reader.warnings.append(
                f"{reader.file}:{element.sourceline}: {error.message}; ignored, as a {kind} "
                "joint has no axis (remove the <axis>)"
            )
            return axis
    axis = reader.numbers(element, "xyz", 3, axis)
    if all(abs(a) < 1e-12 for a in axis):
        raise reader.error(
            element,
            f"joint '{joint}' has a zero axis",
            hint="give <axis xyz> the direction it turns or slides about, such as 0 0 1",
        )
    return axis


def _mujoco_compiler(root: etree._Element, reader: _Reader) -> dict[str, str]:
    """Attributes of ``<mujoco><compiler>`` already in the URDF, to be merged, not duplicated.
    One that asks for masses from the geometry is said not to be applied: the model's masses
    would otherwise differ from MuJoCo's import of the same URDF without a word."""
    result: dict[str, str] = {}
    for mujoco in root.findall("mujoco"):
        for compiler in mujoco.findall("compiler"):
            result.update({str(k): str(v) for k, v in compiler.attrib.items()})
            value = compiler.get("inertiafromgeom", "false").strip()
            if value != "false":
                reader.warnings.append(
                    f'{reader.file}:{compiler.sourceline}: <compiler inertiafromgeom="{value}"> '
                    "is not applied: mjcfbuild takes each link's mass and inertia from its "
                    "<inertial> alone (a link without one gets a placeholder mass); give each "
                    "link its <inertial>"
                )
    return result


def validate_structure(robot: Robot, root: etree._Element, reader: _Reader) -> None:
    """Unique names, existing parents and children, one root, no cycles."""
    if not robot.links:
        raise reader.error(root, "the robot has no links")
    seen = _unique_names("link", [(link.name, link.line) for link in robot.links], reader)
    joint_names = _unique_names("joint", [(j.name, j.line) for j in robot.joints], reader)
    parent_of: dict[str, Joint] = {}
    for joint in robot.joints:
        for end in (joint.parent, joint.child):
            if end not in seen:
                raise InputError(
                    f"joint '{joint.name}' refers to link '{end}', which does not exist",
                    file=reader.file,
                    line=joint.line,
                    hint=_closest(end, seen, "links"),
                )
        if joint.child in parent_of:
            other = parent_of[joint.child]
            raise InputError(
                f"link '{joint.child}' is the child of two joints, "
                f"'{other.name}' and '{joint.name}'",
                file=reader.file,
                line=joint.line,
                hint="a URDF is a tree: every link has at most one parent joint",
            )
        if joint.parent == joint.child:
            raise InputError(
                f"joint '{joint.name}' connects link '{joint.parent}' to itself",
                file=reader.file,
                line=joint.line,
            )
        parent_of[joint.child] = joint
    for joint in robot.joints:
        if joint.mimic is not None and joint.mimic.joint == joint.name:
            raise InputError(
                f"joint '{joint.name}' mimics itself",
                file=reader.file,
                line=joint.line,
                hint="name the joint it follows in <mimic joint=...>",
            )
        if joint.mimic is not None and joint.mimic.joint not in joint_names:
            raise InputError(
                f"joint '{joint.name}' mimics joint '{joint.mimic.joint}', which does not exist",
                file=reader.file,
                line=joint.line,
                hint=_closest(joint.mimic.joint, joint_names, "joints"),
            )
    _refuse_impossible_mimics(robot, reader.file)
    roots = [link.name for link in robot.links if link.name not in parent_of]
    if not roots:
        raise InputError(
            "the links form a cycle: every link has a parent joint",
            file=reader.file,
            line=robot.joints[0].line if robot.joints else None,
        )
    if len(roots) > 1:
        raise _several_roots(robot, roots, reader.file)
    children = robot.child_joints()
    reached = {roots[0]}
    pending = [roots[0]]
    while pending:
        for joint in children[pending.pop()]:
            if joint.child not in reached:
                reached.add(joint.child)
                pending.append(joint.child)
    unreached = [link for link in robot.links if link.name not in reached]
    if unreached:
        raise InputError(
            f"links {', '.join(link.name for link in unreached[:6])} form a cycle "
            "detached from the root",
            file=reader.file,
            line=unreached[0].line,
        )


def _unique_names(kind: str, named: list[tuple[str, int | None]], reader: _Reader) -> set[str]:
    """The names of ``named`` (each with its line); an error at the second of a name given
    twice, naming the line of the first."""
    first_line: dict[str, int | None] = {}
    for name, line in named:
        if name in first_line:
            raise InputError(
                f"{kind} '{name}' is defined twice{first_at(first_line[name])}",
                file=reader.file,
                line=line,
                hint="rename one of them, or remove it",
                first_line=first_line[name],
            )
        first_line[name] = line
    return set(first_line)


def _several_roots(robot: Robot, roots: list[str], file: str) -> InputError:
    """The error for a URDF with more than one root link. The robot's own root carries the
    most links (the first written, where trees tie); the others are the extras, often links an
    optional include adds: the error is at the first of them, and says to connect or remove
    them, never the robot's own root."""
    main = max(roots, key=lambda root: (_tree_size(robot, root), -roots.index(root)))
    extras = [root for root in roots if root != main]
    named = ", ".join(f"'{root}'" for root in extras[:6]) + (", ..." if len(extras) > 6 else "")
    them = "it" if len(extras) == 1 else "them"
    return InputError(
        f"the robot has {len(roots)} root links ({', '.join(roots[:6])}"
        f"{', ...' if len(roots) > 6 else ''}); a URDF has exactly one",
        file=file,
        line=robot.link(extras[0]).line,
        hint=f"connect {named} to the robot (below '{main}') with a joint, or remove {them}",
    )


def _tree_size(robot: Robot, root: str) -> int:
    """How many links hang from ``root`` (itself included)."""
    children = robot.child_joints()
    seen, pending = {root}, [root]
    while pending:
        for joint in children.get(pending.pop(), []):
            if joint.child not in seen:
                seen.add(joint.child)
                pending.append(joint.child)
    return len(seen)


def _refuse_impossible_mimics(robot: Robot, file: str) -> None:
    """A joint that follows a fixed joint (which does not move, and MuJoCo's import removes),
    or a ring of joints each following the next (none of them is driven), is an error at its
    ``<joint>``: MuJoCo built contradictory constraints and no actuator for either."""
    joints = {joint.name: joint for joint in robot.joints}
    for joint in robot.joints:
        if joint.mimic is None or joint.kind == "fixed":
            continue  # a fixed joint's <mimic> moves nothing (genesis' panda_suction has one)
        leader = joints[joint.mimic.joint]
        if leader.kind == "fixed":
            raise InputError(
                f"joint '{joint.name}' mimics joint '{leader.name}', which is fixed",
                file=file,
                line=joint.line,
                hint="name a moving joint in <mimic joint=...>, or remove the <mimic>",
            )
        ring = [joint.name]
        while leader.mimic is not None and leader.name not in ring:
            ring.append(leader.name)
            leader = joints[leader.mimic.joint]
        if leader.name == joint.name:
            raise InputError(
                f"joints {' -> '.join([*ring, joint.name])} mimic each other in a ring, so "
                "none of them is driven",
                file=file,
                line=joint.line,
                hint="one of them must follow no other joint: remove its <mimic>",
            )


def _closest(name: str, candidates: set[str], kind: str) -> str:
    """``did you mean 'x'?`` for the closest of ``candidates``, else the ``kind`` there are."""
    from mjcfbuild.sources.packages import did_you_mean, listing

    suggested = did_you_mean(name, candidates)
    if suggested:
        return suggested.removeprefix("; ")
    return f"{kind}: {listing(sorted(candidates))}"
