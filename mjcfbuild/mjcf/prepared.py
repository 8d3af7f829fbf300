"""The *prepared URDF*: the robot as MuJoCo's URDF import should see it.

Static links are already fused (with their exact poses), inertias already valid, every mesh
already converted and referenced by absolute path, collision geometry already chosen by the
collision policies, and every geom carries a unique temporary name so the assembly can find it
again after import. The ``<mujoco><compiler>`` element (merged with one the URDF may already
have) tells MuJoCo not to fuse, discard or strip anything.

Building it takes two passes: the first decides every geom and which mesh files (at which
scale) they use; the second names those files and assets - identical files once, names unique
without regard to case - and writes the XML.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mjcfbuild.collision.policy import CollisionChoice, collision_policy
from mjcfbuild.errors import InputError, ModelError
from mjcfbuild.markup import xml_attribute
from mjcfbuild.meshes.mshfile import read_file
from mjcfbuild.meshes.product import MeshProduct
from mjcfbuild.mjcf.bodies import WORLD, Body, PlacedShape
from mjcfbuild.numbers import exact_list
from mjcfbuild.urdf.limits import joint_range, unbounded_warning
from mjcfbuild.urdf.transforms import Transform, matrix3, matrix_to_rpy, vec3

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
    policy: str = ""
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
    shell: bool = False
    mesh_id: str = ""
    read_file: str = ""  # what compiles read: the product's binary copy, else product_file


@dataclass
class Material:
    """A MuJoCo material: a colour, and maybe a texture (by published file name)."""

    name: str
    rgba: tuple[float, ...] | None
    texture: str | None = None
    emission: float | None = None


@dataclass
class Prepared:
    """The prepared URDF and the bookkeeping to finish the model after import."""

    urdf: str
    geoms: dict[str, GeomRecord] = field(default_factory=dict)
    meshes: list[MeshAsset] = field(default_factory=list)
    materials: list[Material] = field(default_factory=list)
    textures: dict[str, str] = field(default_factory=dict)
    files: dict[str, str] = field(default_factory=dict)  # published name -> product file
    # published name -> (file, MD5) compiles read for it, where not the product file itself
    reads: dict[str, tuple[str, str]] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


@dataclass
class Decomposition:
    """A finished convex decomposition: its parts' files, by mesh id and parameters."""

    mesh_id: str
    params: dict
    folder: Path
    parts: list[str]
    files: dict[str, str]


@dataclass
class _MeshUse:
    """One mesh file (of a product or decomposition) used at one scale."""

    product_file: str
    md5: str
    stem: str
    scale: tuple
    line: int | None
    uri: str
    shell: bool = False
    mesh_id: str = ""
    read_file: str = ""
    read_md5: str = ""


@dataclass
class _Geom:
    tag: str
    pose: Transform
    record: GeomRecord
    primitive: str | None = None  # geometry XML of a primitive
    mesh: _MeshUse | None = None
    look: tuple | None = None  # (rgba, texture md5, texture file, emission) of a part's look


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
    products: dict[str, MeshProduct],
    product_dirs: dict[str, Path],
    choices: list[CollisionChoice],
    decompositions: list[Decomposition],
    user_compiler: dict[str, str],
    source: str,
    visuals: bool = True,
) -> Prepared:
    """Write the prepared URDF of ``bodies``; ``products`` are mesh summaries by mesh id.

    Without ``visuals`` only collision geometry is written (for the collision matrix, which
    must not depend on visual meshes)."""
    prepared = Prepared(urdf="")
    builder = _Builder(products, product_dirs, decompositions, source, prepared)
    by_link: dict[str, list[CollisionChoice]] = {}
    for choice in choices:
        by_link.setdefault(choice.link, []).append(choice)
    geoms_of = {}
    for body in bodies:
        placed = {(p.link, p.shape.role, p.shape.index): p for p in body.shapes}
        geoms = []
        for shape in body.shapes:
            if visuals and shape.shape.role == "visual":
                geoms += builder.visual(shape, body)
        for frame in body.links:
            for choice in by_link.get(frame.link, []):
                geoms += builder.collision(
                    placed[(choice.link, choice.role, choice.index)], body, choice
                )
        geoms_of[body.name] = geoms
    if builder.flat:
        raise _flat_error(builder.flat, source)
    names = _assign_names(builder.uses, builder.looks, prepared)

    lines = [f"<robot name={xml_attribute(robot_name)}>"]
    counter = 0
    for body in bodies:
        lines.append(f"  <link name={xml_attribute(body.name)}>")
        # A root link named world is MuJoCo's world body, which never moves: its mass means
        # nothing, and an inertia MuJoCo would refuse there stopped the build (drake's
        # Pendulum.urdf), though the repairs skip the world.
        is_world = body.name == WORLD and body.parent is None
        if body.mass is not None and (body.mass.mass > 0 or body.moves) and not is_world:
            lines.extend(_inertial(body))
        for geom in geoms_of[body.name]:
            counter += 1
            temp = f"mjcfbuild_geom_{counter}"
            record = geom.record
            if geom.mesh is not None:
                asset = names.mesh_asset(geom.mesh)
                record.mesh = asset.name
                record.material = names.material_of(geom.look) if geom.look else None
                if record.material is not None:
                    record.rgba = None
                geometry = _mesh_xml(asset)
            else:
                assert geom.primitive is not None, "a geom is a mesh or a primitive"
                geometry = geom.primitive
            prepared.geoms[temp] = record
            lines.append(
                f"    <{geom.tag} name={xml_attribute(temp)}>{_origin(geom.pose)}"
                f"<geometry>{geometry}</geometry></{geom.tag}>"
            )
        lines.append("  </link>")
        if body.joint is not None:
            lines.extend(_joint(body, prepared.warnings, source))
    compiler = {k: v for k, v in user_compiler.items() if k not in IMPORT_COMPILER}
    compiler.update(IMPORT_COMPILER)
    attributes = " ".join(f"{k}={xml_attribute(v)}" for k, v in sorted(compiler.items()))
    lines.append(f"  <mujoco><compiler {attributes}/></mujoco>")
    lines.append("</robot>")
    prepared.urdf = "\n".join(lines) + "\n"
    return prepared


class _Builder:
    """First pass: the geoms of every shape and collision choice, and the files they use."""

    def __init__(self, products, product_dirs, decompositions, source, prepared) -> None:
        self.products = products
        self.product_dirs = product_dirs
        self.decompositions = decompositions
        self.source = source
        self.prepared = prepared
        self.uses: dict[tuple, _MeshUse] = {}
        self.looks: dict[tuple, tuple] = {}
        # Collision meshes whose vertices lie in a plane (or on a line), which MuJoCo cannot
        # take the convex hull of: all of them are named at once (one per file and link).
        self.flat: dict[tuple[str, str], PlacedShape] = {}
        self._flat_files: dict[str, bool] = {}

    def check_flat(self, placed: PlacedShape, geoms: list[_Geom]) -> list[_Geom]:
        """``geoms``; notes ``placed`` as flat where the mesh of one of them is."""
        for geom in geoms:
            if geom.mesh is None or not geom.mesh.product_file.endswith(".obj"):
                continue
            path = geom.mesh.product_file
            if path not in self._flat_files:
                self._flat_files[path] = _is_flat(path)
            if self._flat_files[path]:
                self.flat.setdefault((_rule_name(placed), placed.link), placed)
                break
        return geoms

    def _record(self, placed: PlacedShape, body: Body, role: str, kind: str, policy: str = ""):
        shape = placed.shape
        return GeomRecord(
            body=body.name,
            link=placed.link,
            role=role,
            kind=kind,
            line=shape.line,
            authored_name=shape.name if shape.role == role else None,
            policy=policy,
        )

    def _use(self, mesh_id: str, file: str, md5: str, stem: str, placed: PlacedShape, shell=False):
        if Path(file).is_absolute():  # a decomposition's part
            path, read, read_md5 = file, file, md5
        else:
            folder, files = self.product_dirs[mesh_id], self.products[mesh_id].files
            path = str(folder / file)
            read = str(folder / read_file(file, files))
            read_md5 = files[read_file(file, files)]
        scale = tuple(placed.shape.geometry.scale)
        key = (path, scale)
        if key not in self.uses:
            self.uses[key] = _MeshUse(
                path,
                md5,
                stem,
                scale,
                placed.shape.line,
                placed.shape.geometry.uri or "",
                shell,
                mesh_id,
                read,
                read_md5,
            )
        return self.uses[key]

    def visual(self, placed: PlacedShape, body: Body) -> list[_Geom]:
        geometry = placed.shape.geometry
        colour = placed.shape.material.rgba if placed.shape.material is not None else None
        if geometry.kind != "mesh":
            primitive = self._primitive(placed, "visual")
            if primitive is None:
                return []
            record = self._record(placed, body, "visual", geometry.kind)
            record.rgba = colour
            return [_Geom("visual", placed.pose, record, primitive=primitive)]
        if any(s == 0 for s in geometry.scale):
            return self._zero_size(placed, f"mesh scale {exact_list(geometry.scale)}")
        assert geometry.mesh_id is not None, "resolve gives every mesh an id"
        product = self.products[geometry.mesh_id]
        single = len(product.parts) == 1
        geoms = []
        for index, part in enumerate(product.parts):
            stem = geometry.mesh_id if single else f"{geometry.mesh_id}_{index}"
            shell = abs(part.volume) < 1e-9
            use = self._use(
                geometry.mesh_id, part.file, product.files[part.file], stem, placed, shell
            )
            record = self._record(placed, body, "visual", "mesh")
            record.rgba = colour
            look = None
            if part.rgba is not None or part.texture:
                texture = part.texture
                texture_md5 = product.files[texture] if texture else None
                texture_path = (
                    str(self.product_dirs[geometry.mesh_id] / texture) if texture else None
                )
                rgba = tuple(part.rgba) if part.rgba else None
                look = (rgba, texture_md5, texture_path, part.emission)
                self.looks.setdefault(look, (stem, geometry.mesh_id))
            geoms.append(_Geom("visual", placed.pose, record, mesh=use, look=look))
        return geoms

    def collision(self, placed: PlacedShape, body: Body, choice: CollisionChoice) -> list[_Geom]:
        policy = collision_policy(choice.policy)  # an unknown name is an error, never a default
        geometry = placed.shape.geometry
        record = self._record(placed, body, "collision", geometry.kind, policy.name)
        if geometry.kind != "mesh":
            primitive = self._primitive(placed, "collision")
            return (
                [_Geom("collision", placed.pose, record, primitive=primitive)] if primitive else []
            )
        if any(s == 0 for s in geometry.scale):
            return self._zero_size(placed, f"mesh scale {exact_list(geometry.scale)}", "collision")
        assert geometry.mesh_id is not None, "resolve gives every mesh an id"
        if not self.products[geometry.mesh_id].parts:
            return []  # a file that shows nothing (its mesh task said so): nothing collides
        return policy.geoms(_MeshCollision(self, placed, body, record, choice))

    def _decomposition(self, mesh_id: str, params: dict) -> Decomposition:
        for decomposition in self.decompositions:
            if decomposition.mesh_id == mesh_id and decomposition.params == params:
                return decomposition
        raise KeyError(f"no decomposition of {mesh_id} with {params}")

    def _fitted(
        self, placed: PlacedShape, record: GeomRecord, mesh_id: str, product: MeshProduct
    ) -> _Geom:
        from mjcfbuild.collision.primitives import fit_primitive
        from mjcfbuild.meshes.objfile import read_obj_vertices

        assert product.hull is not None, "the mesh task was given the hull role"
        points = read_obj_vertices(self.product_dirs[mesh_id] / product.hull)
        primitive = fit_primitive(points * np.asarray(placed.shape.geometry.scale))
        offset = Transform(
            matrix3((float(v) for v in row) for row in primitive.transform[:3, :3]),
            vec3(float(v) for v in primitive.transform[:3, 3]),
        )
        record.kind = primitive.kind
        xml = _primitive_xml(primitive.kind, primitive.size)
        return _Geom("collision", placed.pose.compose(offset), record, primitive=xml)

    def _primitive(self, placed: PlacedShape, role: str) -> str | None:
        geometry = placed.shape.geometry
        size = tuple(geometry.size)
        if any(s <= 0 for s in size):
            self._zero_size(placed, f"{geometry.kind} size {exact_list(size)}", role)
            return None
        if geometry.kind == "box":
            return f"<box size={xml_attribute(exact_list(size))}/>"
        if geometry.kind == "sphere":
            return f"<sphere radius={xml_attribute(exact_list(size))}/>"
        # cylinder, and capsule (imported as a cylinder, turned into a capsule after import)
        radius, length = xml_attribute(exact_list(size[:1])), xml_attribute(exact_list(size[1:]))
        return f"<cylinder radius={radius} length={length}/>"

    def _zero_size(self, placed: PlacedShape, what: str, role: str | None = None) -> list:
        shape = placed.shape
        role = role or shape.role
        if role == "visual":
            where = f"{self.source}:{shape.line}" if shape.line else self.source
            self.prepared.warnings.append(
                f"{where}: link '{placed.link}' visual {shape.index} has {what}; dropped it"
            )
            return []
        raise InputError(
            f"link '{placed.link}' {shape.role} {shape.index} has {what}",
            file=self.source,
            line=shape.line,
            hint="give it a positive size, or remove it",
        )


class _MeshCollision:
    """The collision geoms one mesh shape can become, for its policy to choose from
    (``collision.policy.MeshCollision``)."""

    def __init__(
        self,
        builder: _Builder,
        placed: PlacedShape,
        body: Body,
        record: GeomRecord,
        choice: CollisionChoice,
    ) -> None:
        mesh_id = placed.shape.geometry.mesh_id
        assert mesh_id is not None, "resolve gives every mesh an id"
        self.builder = builder
        self.placed = placed
        self.body = body
        self.record = record
        self.choice = choice
        self.mesh_id = mesh_id
        self.product = builder.products[mesh_id]

    def mesh(self) -> list[_Geom]:
        """The mesh's collision product."""
        product, mesh_id = self.product, self.mesh_id
        file = product.collision
        assert file is not None, "the mesh task was given the collision role"
        stem = mesh_id if product.collision_is_whole else f"{mesh_id}_collision"
        shell = abs(product.collision_volume) < 1e-9
        use = self.builder._use(mesh_id, file, product.files[file], stem, self.placed, shell)
        geoms = [_Geom("collision", self.placed.pose, self.record, mesh=use)]
        return self.builder.check_flat(self.placed, geoms) if shell else geoms

    def hull(self) -> list[_Geom]:
        """The mesh's convex hull."""
        product, mesh_id = self.product, self.mesh_id
        assert product.hull is not None, "the mesh task was given the hull role"
        use = self.builder._use(
            mesh_id, product.hull, product.files[product.hull], f"{mesh_id}_hull", self.placed
        )
        return self.builder.check_flat(
            self.placed, [_Geom("collision", self.placed.pose, self.record, mesh=use)]
        )

    def fitted_primitive(self) -> list[_Geom]:
        """The primitive that fits the mesh's hull best."""
        return [self.builder._fitted(self.placed, self.record, self.mesh_id, self.product)]

    def decomposition(self) -> list[_Geom]:
        """A geom per part of the mesh's decomposition with the choice's parameters."""
        builder, mesh_id = self.builder, self.mesh_id
        decomposition = builder._decomposition(mesh_id, self.choice.decompose_params)
        geoms = []
        for index, part in enumerate(decomposition.parts):
            part_record = builder._record(
                self.placed, self.body, "collision", "mesh", self.choice.policy
            )
            use = builder._use(
                mesh_id,
                str(decomposition.folder / part),
                decomposition.files[part],
                f"{mesh_id}_part{index}",
                self.placed,
            )
            geoms.append(_Geom("collision", self.placed.pose, part_record, mesh=use))
        return builder.check_flat(self.placed, geoms)


def _is_flat(path: str) -> bool:
    """Whether the vertices of the OBJ file ``path`` lie in a plane, on a line or at a point."""
    from mjcfbuild.collision.primitives import spans_volume
    from mjcfbuild.meshes.objfile import read_obj_vertices

    return not spans_volume(read_obj_vertices(path))


def _rule_name(placed: PlacedShape) -> str:
    """The name of a shape's mesh that a robot.yaml collision rule's ``meshes`` matches."""
    geometry = placed.shape.geometry
    if geometry.path:
        return Path(geometry.path).name
    return geometry.mesh_id or geometry.uri or ""


def _flat_error(flat: dict[tuple[str, str], PlacedShape], source: str) -> ModelError:
    """One error naming every flat collision mesh, and the robot.yaml rule that fits them."""
    shapes = sorted(flat.values(), key=lambda placed: placed.shape.line or 0)
    first = shapes[0]

    def named(placed: PlacedShape, line: bool = True) -> str:
        where = f" (line {placed.shape.line})" if placed.shape.line and line else ""
        return f"'{_rule_name(placed)}' of link '{placed.link}'{where}"

    files = list(dict.fromkeys(_rule_name(placed) for placed in shapes))
    listed = ", ".join(f'"{name}"' for name in files)
    if len(shapes) == 1:
        what = f"collision mesh {named(first, False)} is flat (its vertices lie in a plane)"
    else:
        others = ", ".join(named(p) for p in shapes[1:])
        what = (
            f"{len(shapes)} collision meshes are flat (their vertices lie in a plane): "
            f"{named(first, False)}, {others}"
        )
    return ModelError(
        f"{what}; MuJoCo cannot take the convex hull it collides with",
        file=source,
        line=first.shape.line,
        hint=(
            f"add to robot.yaml's collision.rules: {{meshes: [{listed}], policy: primitive}} "
            "for a thin box, or policy: none for no contact"
        ),
    )


def _primitive_xml(kind: str, size: tuple) -> str:
    """URDF geometry XML for a fitted primitive given MuJoCo sizes (half extents)."""
    if kind == "box":
        return f"<box size={xml_attribute(exact_list([2 * s for s in size]))}/>"
    if kind == "sphere":
        return f"<sphere radius={xml_attribute(exact_list(size[:1]))}/>"
    radius, length = xml_attribute(exact_list(size[:1])), xml_attribute(exact_list([2 * size[1]]))
    return f"<cylinder radius={radius} length={length}/>"


class _AssetNames:
    """Second pass: names of published files, mesh assets, textures and materials."""

    def __init__(self, prepared: Prepared) -> None:
        self.prepared = prepared
        self.files = _Names()
        self.meshes = _Names()
        self.materials = _Names()
        self.file_by_md5: dict[str, str] = {}
        self.asset_by_key: dict[tuple, MeshAsset] = {}
        self.material_by_look: dict[tuple, str] = {}

    def publish(self, md5: str, stem: str, suffix: str, source: str) -> str:
        if md5 not in self.file_by_md5:
            name = self.files.claim(stem) + suffix
            self.file_by_md5[md5] = name
            self.prepared.files[name] = source
        return self.file_by_md5[md5]

    def mesh_asset(self, use: _MeshUse) -> MeshAsset:
        return self.asset_by_key[(use.md5, use.scale)]

    def material_of(self, look: tuple) -> str | None:
        return self.material_by_look.get(look)


def _assign_names(uses: dict, looks: dict, prepared: Prepared) -> _AssetNames:
    names = _AssetNames(prepared)
    by_file: dict[str, list[_MeshUse]] = {}
    for use in sorted(uses.values(), key=lambda u: (u.stem, u.scale)):
        published = names.publish(use.md5, use.stem, ".obj", use.product_file)
        if use.read_file != use.product_file:
            prepared.reads[published] = (use.read_file, use.read_md5)
        by_file.setdefault(published, []).append(use)
    for published, file_uses in sorted(by_file.items()):
        scales = sorted({use.scale for use in file_uses})
        for use in file_uses:
            key = (use.md5, use.scale)
            if key in names.asset_by_key:
                names.asset_by_key[key].shell |= use.shell
                continue
            suffix = "" if len(scales) == 1 else _scale_suffix(use.scale)
            asset = MeshAsset(
                name=names.meshes.claim(published[:-4] + suffix),
                file=published,
                product_file=use.product_file,
                scale=use.scale,
                line=use.line,
                uri=use.uri,
                shell=use.shell,
                mesh_id=use.mesh_id,
                read_file=use.read_file,
            )
            names.asset_by_key[key] = asset
            prepared.meshes.append(asset)
    for look, (stem, _) in sorted(looks.items(), key=lambda item: item[1][0]):
        rgba, texture_md5, texture_path, emission = look
        texture = None
        if texture_md5 is not None:
            texture = names.publish(texture_md5, f"{stem}_texture", ".png", texture_path)
            prepared.textures[texture[:-4]] = texture
        name = names.materials.claim(stem)
        names.material_by_look[look] = name
        texture_name = texture[:-4] if texture else None
        prepared.materials.append(Material(name, rgba, texture_name, emission))
    return names


def _scale_suffix(scale: tuple) -> str:
    if all(abs(abs(s) - 1.0) < 1e-12 for s in scale):
        flipped = "".join(axis for axis, s in zip("xyz", scale, strict=True) if s < 0)
        return f"_mirror_{flipped}" if flipped else ""
    return "_scale_" + "_".join(f"{s:g}".replace("-", "m").replace(".", "p") for s in scale)


def _mesh_xml(asset: MeshAsset) -> str:
    scale = xml_attribute(exact_list(asset.scale))
    return f"<mesh filename={xml_attribute(asset.read_file)} scale={scale}/>"


def _origin(pose: Transform) -> str:
    if pose.is_identity:
        return ""
    rpy = matrix_to_rpy(pose.rotation)
    xyz = xml_attribute(exact_list(pose.position))
    return f"<origin xyz={xyz} rpy={xml_attribute(exact_list(rpy))}/>"


def _inertial(body: Body) -> list[str]:
    mass = body.mass
    assert mass is not None, "called only for a body with mass properties"
    i = mass.inertia
    values = {
        "ixx": i[0][0],
        "ixy": i[0][1],
        "ixz": i[0][2],
        "iyy": i[1][1],
        "iyz": i[1][2],
        "izz": i[2][2],
    }
    inertia = " ".join(f"{k}={xml_attribute(exact_list([v]))}" for k, v in values.items())
    return [
        "    <inertial>",
        f'      <origin xyz={xml_attribute(exact_list(mass.com))} rpy="0 0 0"/>',
        f"      <mass value={xml_attribute(exact_list([mass.mass]))}/>",
        f"      <inertia {inertia}/>",
        "    </inertial>",
    ]


# MuJoCo wants range[0] < range[1] and ignores a URDF limit with lower == upper, which would turn
# a locked joint into a free one. Such a joint gets this tiny range around its position instead.
LOCKED_JOINT_HALF_RANGE = 1e-6


def _joint(body: Body, warnings: list[str], source: str) -> list[str]:
    joint = body.joint
    assert joint is not None and body.parent is not None, "called only for a child body"
    kind = joint.kind
    lines = [
        f"  <joint name={xml_attribute(joint.name)} type={xml_attribute(kind)}>",
        f"    <parent link={xml_attribute(body.parent)}/>",
        f"    <child link={xml_attribute(body.name)}/>",
    ]
    origin = _origin(body.pose)
    if origin:
        lines.append(f"    {origin}")
    if kind != "fixed":
        lines.append(f"    <axis xyz={xml_attribute(exact_list(joint.axis))}/>")
    limit = joint.limit
    if limit is not None and kind in ("revolute", "prismatic", "continuous"):
        attributes = []
        where = f"{source}:{joint.line}" if joint.line else source
        unbounded = unbounded_warning(joint, where)
        if unbounded:
            warnings.append(unbounded)
        bounds = joint_range(joint)
        if bounds is not None:
            lower, upper = bounds
            if lower == upper:
                warnings.append(
                    f"{where}: joint '{joint.name}' has lower = upper = {lower:g}; locked it with "
                    f"the range {lower:g} +/- {LOCKED_JOINT_HALF_RANGE:g}, since MuJoCo would "
                    "ignore an empty range and leave the joint free"
                )
                lower, upper = lower - LOCKED_JOINT_HALF_RANGE, upper + LOCKED_JOINT_HALF_RANGE
            attributes.append(f"lower={xml_attribute(exact_list([lower]))}")
            attributes.append(f"upper={xml_attribute(exact_list([upper]))}")
        if limit.effort is not None:
            attributes.append(f"effort={xml_attribute(exact_list([limit.effort]))}")
        if limit.velocity is not None:
            attributes.append(f"velocity={xml_attribute(exact_list([limit.velocity]))}")
        lines.append(f"    <limit {' '.join(attributes)}/>")
    if joint.damping or joint.friction:
        lines.append(
            f"    <dynamics damping={xml_attribute(exact_list([joint.damping]))} "
            f"friction={xml_attribute(exact_list([joint.friction]))}/>"
        )
    if joint.mimic is not None:
        mimic = joint.mimic
        lines.append(
            f"    <mimic joint={xml_attribute(mimic.joint)} "
            f"multiplier={xml_attribute(exact_list([mimic.multiplier]))} "
            f"offset={xml_attribute(exact_list([mimic.offset]))}/>"
        )
    lines.append("  </joint>")
    return lines
