"""A COLLADA (.dae) reader for robot meshes: triangles by material, colours, textures.

Written for the DAE files robot descriptions ship (exported from CAD tools and Blender):
``triangles``, ``polylist``, ``polygons``, ``tristrips`` and ``trifans`` primitives, node
transforms (``matrix``, ``translate``, ``rotate``, ``scale``), ``instance_node``, skinned or
morphed geometry through ``instance_controller`` (in its bind pose), materials bound through
``bind_material``, Phong/Lambert/Blinn/constant colours and diffuse textures, mapped with the
texture coordinate set the material's instance binds (``bind_vertex_input``), glows
(``emission``) as a share of their colour (:mod:`mjcfbuild.meshes.collada_looks`), and per-vertex
colours where no material colours the faces (:mod:`mjcfbuild.meshes.collada_colours`). What
the model cannot show is said in :attr:`ColladaMesh.warnings`, a line each. Lines carry no
surface and are left out; any other primitive is an error naming it, never silently dropped.
Ids are resolved as pycollada resolves them (an input's source within its own ``<mesh>``
first), since exporters reuse source ids in every geometry; a reference that stays ambiguous,
a dangling instance, a count that disagrees with its index list or a primitive collapsed to one
point is an error naming the file and line, never a partial or wrong mesh. Where pycollada
departs from the spec, the spec wins: a concave polygon is ear-clipped (as rviz's importer
does; a fan from its first corner covered its notch), an accessor's ``offset`` and unnamed
``<param>`` columns are honoured, and a ``TEXCOORD`` may sit in ``<vertices>``.
Float arrays are parsed in C by numpy, so a 30 MB file loads in a fraction of the time a
general reader takes.

Units (``<unit meter=...>``) are applied. The up axis is reported, and applied only when asked:
real descriptions tag Z-up coordinates ``Y_UP`` (go1's trunk), so the tag alone cannot decide
(:mod:`mjcfbuild.meshes.upaxis` decides from the links that use the file).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import unquote

import numpy as np
from lxml import etree

from mjcfbuild.errors import InputError
from mjcfbuild.meshes.collada_colours import MOST_COLOURS, average, by_colour, face_colours
from mjcfbuild.meshes.collada_looks import RGBA, MaterialLook, material_look
from mjcfbuild.meshes.collada_polygons import fan_triangles, polygon_triangles, strip_triangles
from mjcfbuild.meshes.collada_xml import Reader, floats, ints


@dataclass
class ColladaPart:
    """Triangles of one material, in metres, in the file's root frame."""

    material: str
    vertices: np.ndarray
    faces: np.ndarray
    uv: np.ndarray | None
    rgba: RGBA | None
    texture: Path | None
    emission: float | None = None  # MuJoCo's: a share of the colour the part glows with


@dataclass
class ColladaMesh:
    """Everything read from a DAE file."""

    parts: list[ColladaPart]
    up_axis: str
    unit: float
    warnings: list[str] = field(default_factory=list)  # what the model cannot show, a line each
    # Whether the file names a scene: without one, viewers draw nothing of it, and the model
    # has nothing of it either (no parts, which is no error then).
    scene: bool = True


@dataclass(frozen=True)
class _Binding:
    """An ``<instance_material>``: the material its symbol stands for, and the TEXCOORD set
    each name of the effect's texture coordinates stands for (``<bind_vertex_input>``)."""

    material: str
    texcoord_sets: dict[str, str]


class _Drawing:
    """What walking a file's scene collects: triangles by material, each material's look (read
    once), and warnings."""

    def __init__(self, reader: Reader) -> None:
        self.reader = reader
        # (material, vertex colour) -> pieces (placed vertices, faces, uv); the colour where
        # per-vertex colours colour the faces (collada_colours), else None
        self.groups: dict[tuple[str, RGBA | None], list] = {}
        self.looks: dict[str, MaterialLook] = {}
        self.warnings: list[str] = []

    def look(self, material: str) -> MaterialLook:
        """The look of the material of id ``material`` (what it cannot show said once)."""
        if material not in self.looks:
            self.looks[material] = material_look(self.reader, material)
            for note in self.looks[material].notes:
                self.warn(note)
        return self.looks[material]

    def warn(self, message: str) -> None:
        """Say ``message`` about the file, once."""
        line = f"{self.reader.path.name}: {message}"
        if line not in self.warnings:
            self.warnings.append(line)


def read_collada(path: Path, apply_up_axis: bool = False) -> ColladaMesh:
    """Read a DAE file into parts by material, vertices in metres."""
    reader = Reader(path)
    if reader.root.tag != reader.tag("COLLADA"):
        raise reader.error("not a COLLADA file (its root element is not <COLLADA>)")
    asset = reader.find(reader.root, "asset")
    unit = 1.0
    up_axis = "Y_UP"
    if asset is not None:
        unit_element = reader.find(asset, "unit")
        if unit_element is not None and unit_element.get("meter"):
            unit = _unit(reader, unit_element)
        up_element = reader.find(asset, "up_axis")
        if up_element is not None and up_element.text:
            up_axis = up_element.text.strip()
    root_transform = np.eye(4) * 1.0
    root_transform[:3, :3] *= unit
    if apply_up_axis:
        root_transform = _up_axis_rotation(up_axis) @ root_transform

    drawing = _Drawing(reader)
    scene = reader.find(reader.root, "scene/instance_visual_scene")
    visual_scene = (
        reader.by_url(scene.get("url"), ("visual_scene",), scene) if scene is not None else None
    )
    if scene is not None and visual_scene is None:
        raise reader.error(
            f'<instance_visual_scene url="{scene.get("url")}">: the file has no visual scene '
            "of that id (what the file draws is not known)",
            scene,
        )
    if visual_scene is None:
        geometries = len(reader.findall(reader.root, "library_geometries/geometry"))
        drawing.warn(
            "it has no <scene> (no <instance_visual_scene>), so RViz (whose Assimp refuses the "
            "file) and pycollada draw nothing of it; the model has nothing of it either, to see "
            f"or to collide with (put the {geometries} "
            f"geometr{'y' if geometries == 1 else 'ies'} of its library in a visual scene that "
            "a <scene> names, or re-export the mesh)"
        )
        return ColladaMesh([], up_axis, unit, drawing.warnings, scene=False)
    for node in reader.findall(visual_scene, "node"):
        _walk(drawing, node, root_transform, depth=0)

    _average_excess_colours(drawing)
    parts = []
    for (material, colour), pieces in drawing.groups.items():
        vertices = np.concatenate([p[0] for p in pieces])
        offsets = np.cumsum([0] + [len(p[0]) for p in pieces[:-1]])
        faces = np.concatenate([p[1] + o for p, o in zip(pieces, offsets, strict=True)])
        # A textured material used by one primitive with texture coordinates and one without:
        # the one without reads the texture at (0, 0), as rviz's importer draws it (the texture
        # was dropped for both).
        has_uv = any(p[2] is not None for p in pieces)
        uv = (
            np.concatenate([p[2] if p[2] is not None else np.zeros((len(p[0]), 2)) for p in pieces])
            if has_uv
            else None
        )
        look = drawing.look(material)
        parts.append(
            ColladaPart(
                material,
                vertices,
                faces,
                uv if look.texture else None,
                colour if colour is not None else look.rgba,
                look.texture,
                look.emission,
            )
        )
    return ColladaMesh(parts, up_axis, unit, drawing.warnings)


def _average_excess_colours(drawing: _Drawing) -> None:
    """Past :data:`MOST_COLOURS` vertex colours in the file, each material's vertex-coloured
    faces take their average colour (a part each), with a warning."""
    colours = {colour for _, colour in drawing.groups if colour is not None}
    if len(colours) <= MOST_COLOURS:
        return
    counts: dict[str, list[tuple[RGBA, int]]] = {}  # material -> (colour, faces)
    for (material, colour), pieces in drawing.groups.items():
        if colour is not None:
            counts.setdefault(material, []).append((colour, sum(len(p[1]) for p in pieces)))
    means = {
        material: average([colour for colour, _ in found], [faces for _, faces in found])
        for material, found in counts.items()
    }
    grouped: dict[tuple[str, RGBA | None], list] = {}
    for (material, colour), pieces in drawing.groups.items():
        key = (material, means[material] if colour is not None else None)
        grouped.setdefault(key, []).extend(pieces)
    drawing.groups = grouped
    drawing.warn(
        f"its per-vertex colours (COLOR) hold {len(colours)} colours, more than the "
        f"{MOST_COLOURS} parts mjcfbuild makes of them: the model shows each material's "
        "vertex-coloured faces in their average colour"
    )


def _unit(reader: Reader, element) -> float:
    """The metres in one of the file's units: a positive, finite number, or an error at its
    line (pycollada ignores ``meter="0,001"``, which would make a millimetre mesh a thousand
    times too large)."""
    text = element.get("meter")
    try:
        unit = float(text)
    except ValueError:
        unit = math.nan
    if not (math.isfinite(unit) and unit > 0):
        raise reader.error(
            f'<unit meter="{text}">: the length of the file\'s unit in metres must be a '
            "positive number (0.001 for millimetres)",
            element,
        )
    return unit


def _up_axis_rotation(up_axis: str) -> np.ndarray:
    from mjcfbuild.meshes.upaxis import up_rotation

    rotation = np.eye(4)
    rotation[:3, :3] = up_rotation(up_axis)
    return rotation


def _walk(drawing: _Drawing, node, parent: np.ndarray, depth: int) -> None:
    reader = drawing.reader
    if depth > 64:
        raise reader.error("node hierarchy nested more than 64 levels (a cycle?)")
    transform = parent @ _node_transform(reader, node)
    for instance in reader.findall(node, "instance_geometry"):
        geometry = reader.by_url(instance.get("url"), ("geometry",), instance)
        if geometry is None:  # leaving it out would hand over part of the mesh
            raise reader.error(
                f"<instance_geometry> refers to '{instance.get('url')}', which does not exist",
                instance,
            )
        _add_geometry(drawing, geometry, transform, _bindings(reader, instance))
    for instance in reader.findall(node, "instance_controller"):
        geometry, bind_shape = _controlled_geometry(drawing, instance)
        _add_geometry(drawing, geometry, transform @ bind_shape, _bindings(reader, instance))
    for instance in reader.findall(node, "instance_node"):
        target = reader.by_url(instance.get("url"), ("node",), instance)
        if target is None:
            raise reader.error(
                f"<instance_node> refers to '{instance.get('url')}', which does not exist",
                instance,
            )
        _walk(drawing, target, transform, depth + 1)
    for child in reader.findall(node, "node"):
        _walk(drawing, child, transform, depth + 1)


def _bindings(reader: Reader, instance) -> dict[str, _Binding]:
    """The materials an ``<instance_geometry>`` or ``<instance_controller>`` binds, by symbol."""
    found = {}
    for bound in instance.iter(reader.tag("instance_material")):
        sets = {
            (vertex_input.get("semantic") or "").strip(): vertex_input.get("input_set").strip()
            for vertex_input in reader.findall(bound, "bind_vertex_input")
            if vertex_input.get("input_semantic") == "TEXCOORD"
            and vertex_input.get("input_set") is not None
        }
        found[bound.get("symbol")] = _Binding((bound.get("target") or "").lstrip("#"), sets)
    return found


def _controlled_geometry(drawing: _Drawing, instance):
    """The geometry a ``<controller>`` deforms and the matrix placing it in its bind pose: a
    skin's ``bind_shape_matrix``, as pycollada's scene places a skin, or none for a morph (its
    base mesh). What that leaves out is said once: a skin's joints (neither RViz nor pycollada
    poses a skin; RViz, which leaves the bind shape to the joints, draws it without that
    matrix too) and a morph's targets."""
    reader = drawing.reader
    url = instance.get("url")
    controller = reader.by_url(url, ("controller",), instance)
    if controller is None:
        raise reader.error(
            f"<instance_controller> refers to '{url}', which does not exist", instance
        )
    skin = reader.find(controller, "skin")
    morph = reader.find(controller, "morph")
    deformer = skin if skin is not None else morph
    geometry = (
        reader.by_url(deformer.get("source"), ("geometry",), deformer)
        if deformer is not None
        else None
    )
    if geometry is None:
        raise reader.error(
            f"controller '{controller.get('id')}' has no <skin> or <morph> geometry", controller
        )
    bind_shape = np.eye(4)
    matrix = reader.find(skin, "bind_shape_matrix") if skin is not None else None
    if matrix is not None:
        values = floats(reader, matrix)
        if len(values) != 16:  # pycollada refuses it; left out, the skin would sit elsewhere
            raise reader.error(
                f"the <bind_shape_matrix> of controller '{controller.get('id')}' has "
                f"{len(values)} numbers (a matrix has 16)",
                matrix,
            )
        bind_shape = values.reshape(4, 4)
    name, target = controller.get("id"), geometry.get("id")
    if skin is None:
        drawing.warn(
            f"controller '{name}' morphs geometry '{target}': the model draws its base mesh, "
            "as RViz does, without its morph targets"
        )
    else:
        rviz = "" if np.allclose(bind_shape, np.eye(4)) else " (RViz draws it without that matrix)"
        drawing.warn(
            f"controller '{name}' skins geometry '{target}': the model draws it in its bind "
            f"pose, placed by its <bind_shape_matrix> as pycollada places it{rviz}, not posed "
            "by its joints"
        )
    return geometry, bind_shape


# How many numbers each transform of a node holds.
_TRANSFORM_SIZES = {"matrix": 16, "translate": 3, "rotate": 4, "scale": 3}


def _node_transform(reader: Reader, node) -> np.ndarray:
    transform = np.eye(4)
    for child in node:
        if not isinstance(child.tag, str):
            continue  # comments (a transform commented out), processing instructions
        tag = etree.QName(child).localname
        values = floats(reader, child)
        if tag == "matrix" and len(values) == 16:
            step = values.reshape(4, 4)
        elif tag == "translate" and len(values) == 3:
            step = np.eye(4)
            step[:3, 3] = values
        elif tag == "rotate" and len(values) == 4:
            step = np.eye(4)
            step[:3, :3] = _axis_angle(values[:3], math.radians(values[3]))
        elif tag == "scale" and len(values) == 3:
            step = np.diag([*values, 1.0])
        elif tag in _TRANSFORM_SIZES:
            raise reader.error(
                f"a <{tag}> of node '{node.get('id') or node.get('name')}' with "
                f"{len(values)} numbers (a <{tag}> has {_TRANSFORM_SIZES[tag]})",
                child,
            )
        elif tag in ("lookat", "skew"):
            raise reader.error(
                f"node '{node.get('id') or node.get('name')}' is placed with <{tag}>, which "
                "mjcfbuild does not apply (it would place the mesh wrong without a word)",
                child,
            )
        else:
            continue
        transform = transform @ step
    return transform


def _axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    norm = np.linalg.norm(axis)
    if norm == 0:
        return np.eye(3)
    x, y, z = axis / norm
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return np.array(
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
        ]
    )


def _source_array(reader: Reader, referrer, mesh, cache: dict) -> np.ndarray:
    """The values of the <source> (or <vertices>' POSITION source) that ``referrer`` (an
    <input>) names, as rows of its accessor's stride; ids are looked up in ``mesh`` first."""
    source_id = referrer.get("source") or ""
    key = (source_id, mesh)  # the same id may mean another source in another mesh's scope
    if key in cache:
        return cache[key]
    source = reader.by_url(source_id, ("source", "vertices"), referrer, scope=mesh)
    if source is None:
        raise reader.error(f"source '{source_id}' is missing", referrer)
    if etree.QName(source).localname == "vertices":
        position = next(
            (i for i in reader.findall(source, "input") if i.get("semantic") == "POSITION"), None
        )
        if position is None:
            raise reader.error(f"vertices '{source_id}' have no POSITION input", source)
        result = _source_array(reader, position, source.getparent(), cache)
    else:
        array = reader.find(source, "float_array")
        accessor = reader.find(source, "technique_common/accessor")
        values = floats(reader, array)
        stride = int(accessor.get("stride", "1")) if accessor is not None else 3
        count = (
            int(accessor.get("count", str(len(values) // max(stride, 1))))
            if accessor is not None
            else len(values) // stride
        )
        # The accessor's first value, and its columns: a <param> without a name is skipped.
        offset = accessor.get("offset", "0").strip() if accessor is not None else "0"
        if not offset.isdigit():
            raise reader.error(
                f"the accessor of source '{source_id}' says offset=\"{offset}\", which is no "
                "index (a whole number from 0)",
                accessor,
            )
        start = int(offset)
        params = reader.findall(accessor, "param") if accessor is not None else []
        if params and not any(p.get("name") for p in params):
            raise reader.error(
                f"the accessor of source '{source_id}' names none of its <param>s (COLLADA "
                "reads only named ones), so it gives no values",
                accessor,
            )
        if stride <= 0 or start < 0 or len(values) < start + count * stride:
            raise reader.error(
                f"source '{source_id}' has fewer values than its accessor says", source
            )
        result = values[start : start + count * stride].reshape(count, stride)
        if params and len(params) <= stride and not all(p.get("name") for p in params):
            result = result[:, [k for k, p in enumerate(params) if p.get("name")]]
    cache[key] = result
    return result


_SURFACES = ("triangles", "polylist", "polygons", "tristrips", "trifans")
# Children of <mesh> that are not surfaces: data, and primitives without area.
_NOT_SURFACES = ("source", "vertices", "extra", "lines", "linestrips")


def _add_geometry(
    drawing: _Drawing, geometry, transform: np.ndarray, bindings: dict[str, _Binding]
) -> None:
    reader = drawing.reader
    mesh = reader.find(geometry, "mesh")
    if mesh is None:
        shapes = [etree.QName(e).localname for e in geometry if isinstance(e.tag, str)]
        if any(shape in ("convex_mesh", "spline", "brep") for shape in shapes):
            raise reader.error(
                f"geometry '{geometry.get('id')}' is a <{shapes[0]}>, which mjcfbuild does not "
                "read",
                geometry,
            )
        return
    cache: dict = {}
    for primitive in mesh:
        if not isinstance(primitive.tag, str):
            continue  # comments, processing instructions
        kind = etree.QName(primitive).localname
        if kind in _NOT_SURFACES:
            continue
        if kind not in _SURFACES:
            raise reader.error(
                f"geometry '{geometry.get('id')}' has a <{kind}> primitive, which mjcfbuild "
                "does not read"
            )
        inputs = reader.findall(primitive, "input")
        if not inputs:
            continue
        stride = max(int(i.get("offset", "0")) for i in inputs) + 1
        vertex_input = next((i for i in inputs if i.get("semantic") == "VERTEX"), None)
        if vertex_input is None:
            raise reader.error(f"a <{kind}> of geometry '{geometry.get('id')}' has no VERTEX input")
        symbol = primitive.get("material")
        binding = bindings.get(symbol)
        material = binding.material if binding is not None else symbol or ""
        # uv_per_vertex: a TEXCOORD of the <vertices>, indexed as the positions are
        uv_input, uv_per_vertex = _texcoord_input(
            drawing, geometry, mesh, primitive, vertex_input, material, binding
        )
        if kind == "polygons" and reader.find(primitive, "ph") is not None:
            raise reader.error(
                f"geometry '{geometry.get('id')}' has polygons with holes (<ph>), which "
                "mjcfbuild does not read"
            )
        if kind in ("polygons", "tristrips", "trifans"):  # one <p> per polygon, strip or fan
            polygons = [ints(reader, p) for p in reader.findall(primitive, "p")]
            counts = np.array([len(p) // stride for p in polygons], dtype=np.int64)
            indices = np.concatenate(polygons) if polygons else np.zeros(0, dtype=np.int64)
        else:
            index_lists = reader.findall(primitive, "p")
            if len(index_lists) > 1:  # the schema allows one; reading the first would be partial
                raise reader.error(
                    f"a <{kind}> of geometry '{geometry.get('id')}' has {len(index_lists)} <p> "
                    "index lists (COLLADA allows one)",
                    primitive,
                )
            indices = ints(reader, index_lists[0] if index_lists else None)
            if kind == "polylist":
                vcount = reader.find(primitive, "vcount")
                if vcount is None and index_lists:
                    raise reader.error(
                        f"a <polylist> of geometry '{geometry.get('id')}' has no <vcount> (the "
                        "corners of each polygon)",
                        primitive,
                    )
                counts = ints(reader, vcount)
            else:
                counts = np.full(len(indices) // (3 * stride), 3, dtype=np.int64)
        _check_count(reader, geometry, primitive, len(counts) if len(indices) else 0)
        if len(indices) == 0:
            continue
        if len(indices) % stride or counts.sum() * stride != len(indices):
            raise reader.error(f"the index list of a <{kind}> does not match its inputs", primitive)
        corners = indices.reshape(-1, stride)
        positions = _source_array(reader, vertex_input, mesh, cache)[:, :3]
        vertex_index = corners[:, int(vertex_input.get("offset", "0"))]
        _refuse_outside(reader, geometry, primitive, vertex_index, len(positions), "vertex")
        points = positions[vertex_index]
        _refuse_collapsed(reader, geometry, primitive, points, int(counts.size))
        uv = None
        if uv_input is not None:
            texcoords = _source_array(reader, uv_input, mesh, cache)
            uv_index = (
                vertex_index if uv_per_vertex else corners[:, int(uv_input.get("offset", "0"))]
            )
            if uv_index.size and uv_index.max() < len(texcoords):
                uv = texcoords[uv_index][:, :2]
        if kind == "tristrips":
            faces = strip_triangles(counts)
        elif kind == "trifans":
            faces = fan_triangles(counts)
        else:
            faces = polygon_triangles(counts, points)
        homogeneous = np.hstack([points, np.ones((len(points), 1))])
        placed = (homogeneous @ transform.T)[:, :3]
        if np.linalg.det(transform[:3, :3]) < 0:
            faces = faces[:, ::-1]
        corner_rgb = _corner_colours(
            drawing, geometry, primitive, vertex_input, material, corners, vertex_index, cache
        )
        if corner_rgb is None:
            drawing.groups.setdefault((material, None), []).append((placed, faces, uv))
            continue
        rgb, blended = face_colours(corner_rgb, faces)
        if blended:
            drawing.warn(
                "its per-vertex colours (COLOR) blend across faces, which a MuJoCo mesh "
                "cannot show: the model colours each face with the mean of its corners' colours"
            )
        for colour, chosen in by_colour(rgb):
            piece = (placed, faces[chosen], uv)
            drawing.groups.setdefault((material, colour), []).append(piece)


def _corner_colours(
    drawing: _Drawing,
    geometry,
    primitive,
    vertex_input,
    material: str,
    corners: np.ndarray,
    vertex_index: np.ndarray,
    cache: dict,
) -> np.ndarray | None:
    """The RGB colour of each corner of a primitive, from its COLOR input (set 0 or the
    first); None where it has none, or where its material gives the colour (as RViz shows it,
    which draws no vertex colours), with a warning then."""
    reader = drawing.reader
    mesh = primitive.getparent()
    found = _inputs_of(reader, mesh, primitive, vertex_input, "COLOR")
    if not found:
        return None
    look = drawing.look(material)
    if look.rgba is not None or look.texture is not None:
        drawing.warn(
            "its per-vertex colours (COLOR) are not shown where a material gives the colour, "
            "as RViz shows them (a MuJoCo mesh has no colour per vertex)"
        )
        return None
    chosen, per_vertex = next((f for f in found if _set(f[0]) in ("0", "")), found[0])
    colours = _source_array(reader, chosen, mesh, cache)
    index = vertex_index if per_vertex else corners[:, int(chosen.get("offset", "0"))]
    _refuse_outside(reader, geometry, primitive, index, len(colours), "colour")
    return colours[index][:, :3]


_PLURALS = {"vertex": "vertices", "colour": "colours"}


def _refuse_outside(
    reader: Reader, geometry, primitive, index: np.ndarray, size: int, noun: str
) -> None:
    """An error at ``primitive``'s line where ``index`` points outside a source of ``size``
    entries (a ``noun`` each), as pycollada refuses it."""
    if index.size and (index.max() >= size or index.min() < 0):
        outside = index.min() if index.min() < 0 else index.max()
        raise reader.error(
            f"a <{etree.QName(primitive).localname}> of geometry '{geometry.get('id')}' uses "
            f"{noun} {int(outside)}, but its source has {size} {_PLURALS[noun]} ({noun} index "
            "out of range)",
            primitive,
        )


def _inputs_of(reader: Reader, mesh, primitive, vertex_input, semantic: str) -> list[tuple]:
    """The inputs of ``semantic`` a primitive reads, each with whether it is indexed as the
    positions are: the primitive's own, then those of its ``<vertices>``."""
    own = [i for i in reader.findall(primitive, "input") if i.get("semantic") == semantic]
    vertices = reader.by_url(vertex_input.get("source"), ("vertices",), vertex_input, scope=mesh)
    inputs_there = reader.findall(vertices, "input") if vertices is not None else []
    shared = [i for i in inputs_there if i.get("semantic") == semantic]
    return [(i, False) for i in own] + [(i, True) for i in shared]


def _texcoord_input(
    drawing: _Drawing, geometry, mesh, primitive, vertex_input, material: str, binding
) -> tuple:
    """The TEXCOORD input whose coordinates a primitive's texture reads, and whether it is
    indexed as the positions are (an input of the ``<vertices>``): the set that the material's
    instance binds to the name the texture gives its coordinates (``<bind_vertex_input>``, as
    pycollada reads the binding and the inputs' sets); without a binding, set 0 or the first.
    A bound set the geometry lacks, where it has several, is said in a warning."""
    candidates = _inputs_of(drawing.reader, mesh, primitive, vertex_input, "TEXCOORD")
    if not candidates:
        return None, False
    own = [c for c in candidates if not c[1]]
    default = next((c for c in own if _set(c[0]) in ("0", "")), candidates[0])
    texcoord = drawing.look(material).texcoord
    wanted = binding.texcoord_sets.get(texcoord) if binding is not None and texcoord else None
    if wanted is None:
        return default
    chosen = next((c for c in candidates if _set(c[0]) == wanted), None)
    if chosen is not None:
        return chosen
    if len(candidates) > 1:
        drawing.warn(
            f"material '{material}' maps its texture with texture coordinate set {wanted}, "
            f"which geometry '{geometry.get('id')}' does not have; the model maps it with set "
            f"{_set(default[0]) or 0} (bind a set the geometry has, or re-export the mesh)"
        )
    return default


def _set(texcoord_input) -> str:
    """The ``set`` an input says it belongs to ("" where it says none)."""
    return (texcoord_input.get("set") or "").strip()


def _check_count(reader: Reader, geometry, primitive, found: int) -> None:
    """Refuse a primitive whose ``count`` says more or fewer faces (polygons, strips) than its
    index list holds: a truncated or hand-edited file, which would be read in part."""
    declared = primitive.get("count")
    if declared is None or not declared.strip().isdigit() or int(declared) == found:
        return
    raise reader.error(
        f"a <{etree.QName(primitive).localname}> of geometry '{geometry.get('id')}' says "
        f'count="{declared.strip()}" but its index list holds {found}',
        primitive,
    )


def _refuse_collapsed(reader: Reader, geometry, primitive, points: np.ndarray, count: int) -> None:
    """Refuse a primitive of several faces whose corners all lie on one point: no exporter
    writes one on purpose, and it is what a source read from the wrong place looks like."""
    if count > 1 and len(points) and np.all(points == points[0]):
        raise reader.error(
            f"all {count} faces of a <{etree.QName(primitive).localname}> of geometry "
            f"'{geometry.get('id')}' collapse to a single point",
            primitive,
        )


def referenced_files(path: Path) -> list[Path]:
    """Texture files a DAE refers to (only those that exist)."""
    return [p for p in named_files(path) if p.is_file()]


def named_files(path: Path) -> list[Path]:
    """The files a DAE's images name (``<image><init_from>``, or its ``<ref>`` in COLLADA
    1.5), whether they exist or not."""
    try:
        reader = Reader(path)
    except InputError:
        return []
    found = []
    for image in reader.root.iter(reader.tag("image")):
        init = next(image.iter(reader.tag("init_from")), None)
        if init is None:
            continue
        ref = next(init.iter(reader.tag("ref")), None)
        text = unquote(((ref.text if ref is not None else init.text) or "").strip())
        if not text or text.startswith("#"):
            continue
        if text.startswith("file://"):
            text = text[len("file://") :]
        found.append(Path(text) if Path(text).is_absolute() else path.parent / text)
    return sorted(set(found))
