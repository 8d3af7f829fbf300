"""What a description file is, told from its content: xacro, plain URDF, or something else.

``mjcfbuild init`` writes ``xacro:`` or ``urdf:`` from this, and the build refuses a plain URDF
source that xacro would have to expand; both use the one rule here.
"""

from __future__ import annotations

import re
import struct
from pathlib import Path

# xacro processes an element whose tag starts with "xacro:" (expand.is_xacro_element) and
# evaluates ${...} and $(...) in attribute values; a namespace declaration alone does nothing.
# $(...) counts only with one of xacro's substitution commands: anything else in $( ) xacro
# refuses too, so it is text of the URDF (a name like "$(touch x)"), not xacro.
_SUBSTITUTION = rb"\$(?:\{|\((?:find|arg|env|optenv|anon|eval|dirname|cwd)\b)"
_XACRO_USE = re.compile(
    rb"<(xacro:[A-Za-z_][\w.-]*)"
    rb"|=\s*(?:\"[^\"<]*?("
    + _SUBSTITUTION
    + rb"[^\"]*?)\"|'[^'<]*?("
    + _SUBSTITUTION
    + rb"[^']*?)')"
)
_ROOT = re.compile(rb"<([A-Za-z_][\w:.-]*)")
_ROOTS = {
    "robot": None,
    "sdf": "an SDF model",
    "mujoco": "an MJCF model",
    "COLLADA": "a COLLADA (DAE) mesh",
    "gazebo": "a Gazebo file",
}
# Files a user may pass by mistake, by their first bytes.
_BINARY_KINDS = (
    (b"\x89PNG\r\n\x1a\n", "a PNG image"),
    (b"\xff\xd8\xff", "a JPEG image"),
    (b"GIF8", "a GIF image"),
    (b"%PDF-", "a PDF document"),
    (b"PK\x03\x04", "a ZIP archive"),
    (b"\x1f\x8b", "a gzip archive"),
    (b"\x7fELF", "a program"),
)
_MESH_EXTENSIONS = {
    ".stl": "an STL mesh",
    ".obj": "an OBJ mesh",
    ".dae": "a COLLADA (DAE) mesh",
    ".glb": "a glTF (GLB) mesh",
    ".gltf": "a glTF mesh",
    ".ply": "a PLY mesh",
}


def xacro_evidence(data: bytes) -> tuple[str, int] | None:
    """The first thing in ``data`` only xacro can read, as (what, line): a ``<xacro:...>``
    element or a ``${...}``/``$(...)`` substitution in an attribute; None for a plain URDF.
    Comments do not count (talos's URDF comments out a property)."""
    for match in _XACRO_USE.finditer(data):
        if _in_comment(data, match.start()):
            continue
        line = data.count(b"\n", 0, match.start()) + 1
        if match.group(1):
            return f"<{match.group(1).decode('utf-8', 'replace')}>", line
        used = (match.group(2) or match.group(3)).decode("utf-8", "replace")
        closing = "}" if used.startswith("${") else ")"
        end = used.find(closing)
        return (used[: end + 1] if end > 0 else used[:20]), line
    return None


def _in_comment(data: bytes, position: int) -> bool:
    """Whether ``position`` lies inside an XML comment."""
    opened = data.rfind(b"<!--", 0, position)
    return opened >= 0 and data.find(b"-->", opened, position) < 0


def not_a_description(path: Path, data: bytes) -> str | None:
    """What ``path`` (with content ``data``) is when it is not a URDF or xacro file ("an STL
    mesh", "an SDF model", "not XML"), or None when it is one."""
    mesh = mesh_kind(path, data)
    if mesh is not None:
        return mesh
    head = data[:4096]
    for magic, kind in _BINARY_KINDS:
        if head.startswith(magic):
            return kind
    if b"\0" in head:
        return "a binary file"  # its bytes may hold a '<' that is no XML element
    root = _root_tag(head)
    if root is not None:
        local = root.split(":")[-1]
        return _ROOTS.get(local, f"an XML file whose root element is <{root}>, not <robot>")
    if not data.strip():
        return "an empty file"
    return _MESH_EXTENSIONS.get(
        path.suffix.lower(), "a binary file" if b"\0" in head else "not XML"
    )


def mesh_kind(path: Path, data: bytes) -> str | None:
    """What mesh ``path`` (with content ``data``) is ("an STL mesh"), by its content, or by
    its extension where the content is not XML; None when it is no mesh."""
    head = data[:4096]
    if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack("<I", data[80:84])[0]:
        return "an STL mesh"  # binary STL: a header, a count and 50 bytes per triangle
    stripped = head.lstrip()
    if stripped[:5].lower() == b"solid" and (b"facet" in head or b"endsolid" in head):
        return "an STL mesh"
    if head.startswith(b"glTF"):
        return "a glTF (GLB) mesh"
    if head.startswith((b"ply\n", b"ply\r\n")):
        return "a PLY mesh"
    if stripped.startswith(b"{") and b'"asset"' in data:
        return "a glTF mesh"
    root = _root_tag(head)
    if root is not None:
        return "a COLLADA (DAE) mesh" if root.split(":")[-1] == "COLLADA" else None
    if re.search(rb"(?m)^\s*(v|vn|vt|f)\s+-?[0-9]", head):
        return "an OBJ mesh"
    return _MESH_EXTENSIONS.get(path.suffix.lower()) if data.strip() else None


def _root_tag(head: bytes) -> str | None:
    """The root element's tag in the start of an XML file, skipping the declaration, comments
    and doctype; None when no element starts there."""
    position = 0
    while True:
        position = head.find(b"<", position)
        if position < 0:
            return None
        if head.startswith(b"<!--", position):
            end = head.find(b"-->", position)
            if end < 0:
                return None
            position = end + 3
        elif head.startswith((b"<?", b"<!"), position):
            position += 2
        else:
            match = _ROOT.match(head, position)
            return match.group(1).decode("utf-8", "replace") if match else None


def not_a_manifest(path: Path, data: bytes) -> str | None:
    """What ``path`` (with content ``data``) is when it is plainly no robot.yaml: a URDF or
    xacro file, a mesh, an image, other XML or binary data; None where it may be YAML."""
    text = data.lstrip(b"\xef\xbb\xbf \t\r\n")
    # Text in another encoding is a manifest saved wrongly: its reader says where.
    binary = b"\0" in data[:4096] or any(data.startswith(magic) for magic, _ in _BINARY_KINDS)
    xml = re.match(rb"<[?!A-Za-z_]", text) is not None  # not YAML's merge key, <<:
    if not (binary or xml or mesh_kind(path, data) is not None):
        return None
    kind = not_a_description(path, data)
    if kind is not None:
        return kind
    return "a xacro file" if xacro_evidence(data) is not None else "a URDF"


def not_an_mjcf(path: Path, data: bytes) -> str | None:
    """What ``path`` (with content ``data``) is when it is not an MJCF model (its root element
    is not <mujoco>): a URDF or xacro file (which MuJoCo would read as a URDF), a mesh, an
    image...; None for an MJCF model, or text in which no element starts (MuJoCo's to judge)."""
    head = data[:4096]
    binary = b"\0" in head or any(head.startswith(magic) for magic, _ in _BINARY_KINDS)
    if binary or mesh_kind(path, data) is not None:
        return not_a_description(path, data)
    root = _root_tag(data[: 1 << 20])  # past a licence comment of any length
    local = root.split(":")[-1] if root is not None else None
    if local is None or local == "mujoco":
        return None
    if local == "robot":
        return "a xacro file" if xacro_evidence(data) is not None else "a URDF"
    return _ROOTS.get(local) or f"an XML file whose root element is <{root}>, not <mujoco>"
