"""The *prepared URDF*: the robot as MuJoCo's URDF import should see it.

Static links are already fused (with their exact poses), inertias already valid, every mesh
already converted and referenced by absolute path, every geom carries a unique temporary name
so the assembly can find it again after import, and the ``<mujoco><compiler>`` element (merged
with one the URDF may already have) tells MuJoCo not to fuse, discard or strip anything.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from xml.sax.saxutils import quoteattr

from mjcfbuild.errors import InputError
from mjcfbuild.mjcf.bodies import Body, PlacedShape
from mjcfbuild.numbers import exact_list
from mjcfbuild.urdf.transforms import Transform, matrix_to_rpy

# Compiler settings the import needs, whatever the URDF's own <mujoco> says.
IMPORT_COMPILER = {
    "angle": "radian",
    "discardvisual": "false",
    "fusestatic": "false",
    "strippath": "false",
    "inertiafromgeom": "false",
}


@dataclass
class GeomRecord:
    """What the assembly needs to know about one geom it asked MuJoCo to import."""

    body: str
    link: str
    role: str
    kind: str
    line: int | None
    authored_name: str | None
    rgba: tuple[float, ...] | None = None
    material: str | None = None
    mesh: str | None = None


@dataclass
class MeshAsset:
    """A MuJoCo mesh asset: a published file at one scale."""

    name: str
    file: str
    product_file: str
    scale: tuple[float, float, float]
    line: int | None = None
    uri: str = ""


@dataclass
class Prepared:
    """The prepared URDF and the bookkeeping to finish the model after import."""

    urdf: str
    geoms: dict[str, GeomRecord] = field(default_factory=dict)
    meshes: list[MeshAsset] = field(default_factory=list)
    materials: dict[str, tuple[float, ...]] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


class _Names:
    """Hands out names unique without regard to case, in the order they are asked for."""

    def __init__(self) -> None:
        self.used: set[str] = set()

    def claim(self, wanted: str) -> str:
        name, index = wanted, 2
        while name.lower() in self.used:
            name, index = f"{wanted}_{index}", index + 1
        self.used.add(name.lower())
        return name


def prepare(
    robot_name: str,
    bodies: list[Body],
    products: dict[str, dict],
    product_dirs: dict[str, Path],
    user_compiler: dict[str, str],
    source: str,
) -> Prepared:
    """Write the prepared URDF of ``bodies``; ``products`` are mesh summaries by mesh id."""
    prepared = Prepared(urdf="")
    assets = _plan_mesh_assets(bodies, products, product_dirs)
    prepared.meshes = sorted(assets.values(), key=lambda a: a.name)
    lines = [f"<robot name={quoteattr(robot_name)}>"]
    counter = 0
    for body in bodies:
        lines.append(f"  <link name={quoteattr(body.name)}>")
        if body.mass is not None and (body.mass.mass > 0 or body.moves):
            lines.extend(_inertial(body))
        for placed in body.shapes:
            for element in _shape_elements(placed, body, products, assets, source, prepared):
                counter += 1
                temp = f"mjcfbuild_geom_{counter}"
                prepared.geoms[temp] = element.record
                lines.append(element.xml(temp))
        lines.append("  </link>")
        if body.joint is not None:
            lines.extend(_joint(body))
    compiler = {
        **{k: v for k, v in user_compiler.items() if k not in IMPORT_COMPILER},
        **IMPORT_COMPILER,
    }
    attributes = " ".join(f"{k}={quoteattr(v)}" for k, v in sorted(compiler.items()))
    lines.append(f"  <mujoco><compiler {attributes}/></mujoco>")
    lines.append("</robot>")
    prepared.urdf = "\n".join(lines) + "\n"
    return prepared


def _plan_mesh_assets(
    bodies: list[Body], products: dict[str, dict], product_dirs: dict[str, Path]
) -> dict[tuple[str, str, tuple], MeshAsset]:
    """One mesh asset per (mesh id, product file, scale) the model uses, uniquely named."""
    uses: dict[tuple[str, str], set[tuple]] = {}
    first_use: dict[tuple[str, str], tuple[int | None, str]] = {}
    for body in bodies:
        for placed in body.shapes:
            geometry = placed.shape.geometry
            if geometry.kind != "mesh":
                continue
            product = products[geometry.mesh_id]
            files = (
                [part["file"] for part in product["parts"]]
                if placed.shape.role == "visual"
                else [product["collision"]]
            )
            for file in files:
                uses.setdefault((geometry.mesh_id, file), set()).add(tuple(geometry.scale))
                first_use.setdefault((geometry.mesh_id, file), (placed.shape.line, geometry.uri))
    file_names, mesh_names = _Names(), _Names()
    result = {}
    for mesh_id, file in sorted(uses):
        published = file_names.claim(_published_stem(mesh_id, file)) + ".obj"
        scales = sorted(uses[(mesh_id, file)])
        for scale in scales:
            suffix = "" if len(scales) == 1 else _scale_suffix(scale)
            asset = MeshAsset(
                name=mesh_names.claim(published[:-4] + suffix),
                file=published,
                product_file=str(product_dirs[mesh_id] / file),
                scale=scale,
                line=first_use[(mesh_id, file)][0],
                uri=first_use[(mesh_id, file)][1] or "",
            )
            result[(mesh_id, file, scale)] = asset
    return result


def _published_stem(mesh_id: str, product_file: str) -> str:
    """``link3`` for a single-material mesh, ``link3_0``... for parts, ``link3_collision``."""
    if product_file == "mesh.obj":
        return mesh_id
    if product_file == "collision.obj":
        return f"{mesh_id}_collision"
    return f"{mesh_id}_{product_file.removeprefix('part').removesuffix('.obj')}"


def _scale_suffix(scale: tuple) -> str:
    if all(abs(abs(s) - 1.0) < 1e-12 for s in scale):
        flipped = "".join(axis for axis, s in zip("xyz", scale, strict=True) if s < 0)
        return f"_mirror_{flipped}" if flipped else ""
    return "_scale_" + "_".join(f"{s:g}".replace("-", "m").replace(".", "p") for s in scale)


@dataclass
class _Element:
    tag: str
    pose: Transform
    geometry_xml: str
    record: GeomRecord

    def xml(self, name: str) -> str:
        return (
            f"    <{self.tag} name={quoteattr(name)}>{_origin(self.pose)}"
            f"<geometry>{self.geometry_xml}</geometry></{self.tag}>"
        )


def _shape_elements(
    placed: PlacedShape,
    body: Body,
    products: dict[str, dict],
    assets: dict,
    source: str,
    prepared: Prepared,
) -> list[_Element]:
    shape = placed.shape
    geometry = shape.geometry
    role = shape.role
    colour = shape.material.rgba if shape.material is not None else None

    def record(**extra) -> GeomRecord:
        return GeomRecord(
            body=body.name,
            link=placed.link,
            role=role,
            kind=geometry.kind,
            line=shape.line,
            authored_name=shape.name,
            **extra,
        )

    if geometry.kind == "mesh":
        product = products[geometry.mesh_id]
        scale = tuple(geometry.scale)
        if any(s == 0 for s in scale):
            return _zero_size(placed, source, prepared, f"mesh scale {exact_list(scale)}")
        if role == "collision":
            asset = assets[(geometry.mesh_id, product["collision"], scale)]
            return [_Element(role, placed.pose, _mesh_xml(asset), record(mesh=asset.name))]
        elements = []
        for part in product["parts"]:
            asset = assets[(geometry.mesh_id, part["file"], scale)]
            material = None
            rgba = colour
            if part["rgba"] is not None:
                material = asset.file[:-4]
                prepared.materials[material] = tuple(part["rgba"])
                rgba = None
            elements.append(
                _Element(
                    role,
                    placed.pose,
                    _mesh_xml(asset),
                    record(rgba=rgba, material=material, mesh=asset.name),
                )
            )
        return elements
    size = tuple(geometry.size)
    if any(s <= 0 for s in size):
        return _zero_size(placed, source, prepared, f"{geometry.kind} size {exact_list(size)}")
    if geometry.kind == "box":
        xml = f"<box size={quoteattr(exact_list(size))}/>"
    elif geometry.kind == "sphere":
        xml = f"<sphere radius={quoteattr(exact_list(size))}/>"
    else:  # cylinder, and capsule (imported as a cylinder, turned into a capsule after import)
        radius, length = quoteattr(exact_list(size[:1])), quoteattr(exact_list(size[1:]))
        xml = f"<cylinder radius={radius} length={length}/>"
    return [_Element(role, placed.pose, xml, record(rgba=colour if role == "visual" else None))]


def _zero_size(placed: PlacedShape, source: str, prepared: Prepared, what: str) -> list[_Element]:
    shape = placed.shape
    where = f"{source}:{shape.line}" if shape.line else source
    if shape.role == "visual":
        prepared.warnings.append(
            f"{where}: link '{placed.link}' visual {shape.index} has {what}; dropped it"
        )
        return []
    raise InputError(
        f"link '{placed.link}' collision {shape.index} has {what}",
        file=source,
        line=shape.line,
        hint="give it a positive size, or remove the <collision>",
    )


def _mesh_xml(asset: MeshAsset) -> str:
    scale = quoteattr(exact_list(asset.scale))
    return f"<mesh filename={quoteattr(asset.product_file)} scale={scale}/>"


def _origin(pose: Transform) -> str:
    if pose.is_identity:
        return ""
    rpy = matrix_to_rpy(pose.rotation)
    return f"<origin xyz={quoteattr(exact_list(pose.position))} rpy={quoteattr(exact_list(rpy))}/>"


def _inertial(body: Body) -> list[str]:
    mass = body.mass
    i = mass.inertia
    values = {
        "ixx": i[0][0],
        "ixy": i[0][1],
        "ixz": i[0][2],
        "iyy": i[1][1],
        "iyz": i[1][2],
        "izz": i[2][2],
    }
    inertia = " ".join(f"{k}={quoteattr(exact_list([v]))}" for k, v in values.items())
    return [
        "    <inertial>",
        f'      <origin xyz={quoteattr(exact_list(mass.com))} rpy="0 0 0"/>',
        f"      <mass value={quoteattr(exact_list([mass.mass]))}/>",
        f"      <inertia {inertia}/>",
        "    </inertial>",
    ]


def _joint(body: Body) -> list[str]:
    joint = body.joint
    kind = joint.kind
    lines = [
        f"  <joint name={quoteattr(joint.name)} type={quoteattr(kind)}>",
        f"    <parent link={quoteattr(body.parent)}/>",
        f"    <child link={quoteattr(body.name)}/>",
    ]
    origin = _origin(body.pose)
    if origin:
        lines.append(f"    {origin}")
    if kind != "fixed":
        lines.append(f"    <axis xyz={quoteattr(exact_list(joint.axis))}/>")
    limit = joint.limit
    if limit is not None and kind in ("revolute", "prismatic", "continuous"):
        attributes = []
        if kind != "continuous":
            attributes.append(f"lower={quoteattr(exact_list([limit.lower or 0.0]))}")
            attributes.append(f"upper={quoteattr(exact_list([limit.upper or 0.0]))}")
        if limit.effort is not None:
            attributes.append(f"effort={quoteattr(exact_list([limit.effort]))}")
        if limit.velocity is not None:
            attributes.append(f"velocity={quoteattr(exact_list([limit.velocity]))}")
        lines.append(f"    <limit {' '.join(attributes)}/>")
    if joint.damping or joint.friction:
        lines.append(
            f"    <dynamics damping={quoteattr(exact_list([joint.damping]))} "
            f"friction={quoteattr(exact_list([joint.friction]))}/>"
        )
    if joint.mimic is not None:
        mimic = joint.mimic
        lines.append(
            f"    <mimic joint={quoteattr(mimic.joint)} "
            f"multiplier={quoteattr(exact_list([mimic.multiplier]))} "
            f"offset={quoteattr(exact_list([mimic.offset]))}/>"
        )
    lines.append("  </joint>")
    return lines
