"""Masses from geometry, for links without one (robot.yaml's ``inertia.missing: geometry``).

MuJoCo's own URDF import gives a link with no ``<inertial>`` the mass, centre of mass and
inertia of its collision geometry at density 1000 kg/m^3 (compiler ``inertiafromgeom="auto"``;
visual geometry is discarded). mjcfbuild does not invent masses unasked: by default such a link
gets a placeholder (``inertia.min_mass``). With ``missing: geometry`` each link without a mass
(no ``<inertial>``, or mass 0) gets what MuJoCo computes from its own geoms, each link alone, in
its own frame: its collision geometry (its visual geometry where it has none) at
``inertia.density``, meshes as the build converted them (their collision file: every triangle
in one mesh). The masses are then fused with the link's fixed-joint neighbours as any
``<inertial>`` is, which is what MuJoCo's import does with ``fusestatic``.

Links in MuJoCo's world body (a ``world`` root and what is fixed to it) are left alone: the
world drops their mass. A mesh that encloses no volume (an open shell) weighs nothing; a link
whose geometry encloses none keeps the placeholder, with a warning.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from mjcfbuild.meshes.product import MeshProduct
from mjcfbuild.mjcf.bodies import WORLD, build_bodies
from mjcfbuild.urdf.model import Inertial, Link, Pose, Robot, Shape, Vec3
from mjcfbuild.urdf.transforms import Transform

Tensor = tuple[float, float, float, float, float, float]  # ixx, ixy, ixz, iyy, iyz, izz
# What robot.yaml says, for the warnings.
SETTING = "inertia.missing: geometry"
# A mesh whose volume is below this (m^3, as the mesh task measures it) encloses nothing.
SHELL_VOLUME = 1e-9


@dataclass(frozen=True)
class GeometryMass:
    """The mass one link was given from its geometry, in its own frame (the centre of mass,
    and the inertia tensor about it: ixx, ixy, ixz, iyy, iyz, izz)."""

    link: str
    mass: float
    com: Vec3
    inertia: Tensor
    geometry: str  # "collision" or "visual": which of the link's geometry weighs it
    density: float
    line: int | None = None  # of the link (or of its massless <inertial>)

    def to_dict(self) -> dict:
        """As assembly.json holds it."""
        return {
            "link": self.link,
            "mass": self.mass,
            "com": list(self.com),
            "inertia": list(self.inertia),
            "geometry": self.geometry,
            "density": self.density,
            "line": self.line,
        }

    @classmethod
    def from_dict(cls, data: dict) -> GeometryMass:
        """The record ``to_dict`` wrote."""
        return cls(
            link=data["link"],
            mass=float(data["mass"]),
            com=(float(data["com"][0]), float(data["com"][1]), float(data["com"][2])),
            inertia=_tensor(data["inertia"]),
            geometry=data["geometry"],
            density=float(data["density"]),
            line=data.get("line"),
        )

    def inertial(self) -> Inertial:
        """The ``<inertial>`` the link is given."""
        return Inertial(Pose(self.com, (0.0, 0.0, 0.0)), self.mass, self.inertia, self.line)

    def describe(self, source: str) -> str:
        """The build's warning line, at the link's URDF line."""
        where = f"{source}:{self.line}" if self.line else source
        which = (
            "its collision geometry"
            if self.geometry == "collision"
            else "its visual geometry (it has no <collision>)"
        )
        return (
            f"{where}: link '{self.link}' has no <inertial>: given {self.mass:.4g} kg from "
            f"{which} at {self.density:g} kg/m^3 ({SETTING})"
        )


def massless(link: Link) -> bool:
    """Whether ``link`` has no mass in the URDF: no ``<inertial>``, or mass 0."""
    return link.inertial is None or link.inertial.mass == 0


def weighed_shapes(link: Link) -> tuple[str, list[Shape]]:
    """Which of ``link``'s geometry gives it a mass, and its shapes: the collisions, else the
    visuals."""
    if link.collisions:
        return "collision", list(link.collisions)
    return "visual", list(link.visuals)


def weighed_meshes(robot: Robot) -> set[str]:
    """The mesh ids whose collision file (every triangle in one mesh) the masses of
    ``robot``'s links without one are computed from: their mesh tasks must make it."""
    found = set()
    for link in robot.links:
        if not massless(link):
            continue
        for shape in weighed_shapes(link)[1]:
            if shape.geometry.kind == "mesh" and shape.geometry.mesh_id is not None:
                found.add(shape.geometry.mesh_id)
    return found


def with_geometry_masses(
    robot: Robot,
    products: dict[str, MeshProduct],
    product_dirs: dict[str, Path],
    density: float,
    fuse_static: bool,
    free_joint: bool,
) -> tuple[Robot, list[GeometryMass], list[str]]:
    """``robot`` with each link without a mass given that of its geometry, the masses given
    (in URDF order) and warnings for links whose geometry encloses no volume."""
    in_world = {
        frame.link
        for body in build_bodies(robot, fuse_static, free_joint=free_joint)
        if body.name == WORLD and body.parent is None
        for frame in body.links
    }
    wanted: dict[str, tuple[str, list[tuple[Shape, str | None]]]] = {}
    warnings = []
    for link in robot.links:
        if link.name in in_world or not massless(link):
            continue
        role, shapes = weighed_shapes(link)
        if not shapes:
            continue  # nothing to weigh: the placeholder, as before
        usable = [(shape, _mesh_file(shape, products, product_dirs)) for shape in shapes]
        usable = [(shape, file) for shape, file in usable if file != "" and _has_size(shape)]
        if not usable:
            where = f"{robot.source}:{_line(link)}" if _line(link) else robot.source
            warnings.append(
                f"{where}: link '{link.name}' has no <inertial>, and its {role} geometry "
                f"encloses no volume, so {SETTING} cannot give it a mass: it keeps the "
                "placeholder mass (inertia.min_mass); give it an <inertial>"
            )
            continue
        wanted[link.name] = (role, usable)
    if not wanted:
        return robot, [], warnings
    computed = _compile(wanted, density)
    given = []
    links = []
    for link in robot.links:
        if link.name in computed:
            mass, com, inertia = computed[link.name]
            record = GeometryMass(
                link.name, mass, com, inertia, wanted[link.name][0], density, _line(link)
            )
            given.append(record)
            link = replace(link, inertial=record.inertial())
        links.append(link)
    return replace(robot, links=links), given, warnings


def with_given(robot: Robot, given: list[GeometryMass]) -> Robot:
    """``robot`` with the masses a build gave its links from their geometry (the check's view
    of the masses the model should have)."""
    if not given:
        return robot
    by_link = {record.link: record for record in given}
    links = [
        replace(link, inertial=by_link[link.name].inertial()) if link.name in by_link else link
        for link in robot.links
    ]
    return replace(robot, links=links)


def _tensor(values: list) -> Tensor:
    ixx, ixy, ixz, iyy, iyz, izz = (float(v) for v in values)
    return (ixx, ixy, ixz, iyy, iyz, izz)


def _line(link: Link) -> int | None:
    return link.inertial.line if link.inertial is not None else link.line


def _has_size(shape: Shape) -> bool:
    geometry = shape.geometry
    if geometry.kind == "mesh":
        return all(s != 0 for s in geometry.scale)
    return bool(geometry.size) and all(s > 0 for s in geometry.size)


def _mesh_file(
    shape: Shape, products: dict[str, MeshProduct], product_dirs: dict[str, Path]
) -> str | None:
    """The file MuJoCo weighs a mesh shape from (None for a primitive; '' for a mesh that
    encloses no volume, or shows nothing)."""
    geometry = shape.geometry
    if geometry.kind != "mesh":
        return None
    product = products.get(geometry.mesh_id or "")
    if product is None or product.collision is None or not product.parts:
        return ""
    if abs(product.collision_volume) < SHELL_VOLUME:
        return ""
    from mjcfbuild.meshes.mshfile import read_file

    folder = product_dirs[geometry.mesh_id or ""]
    return str(folder / read_file(product.collision, product.files))


def _compile(
    wanted: dict[str, tuple[str, list[tuple[Shape, str | None]]]], density: float
) -> dict[str, tuple[float, Vec3, Tensor]]:
    """Each link's (mass, centre of mass, inertia tensor) as MuJoCo computes them from its
    geoms: one body per link, in the link's frame, compiled with ``inertiafromgeom``."""
    import mujoco
    import numpy as np

    spec = mujoco.MjSpec()
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_TRUE
    meshes: dict[tuple[str, tuple[float, ...]], str] = {}
    names = []
    for index, (link, (_, shapes)) in enumerate(wanted.items()):
        body = spec.worldbody.add_body(name=f"link{index}")
        names.append((link, body.name))
        for shape, file in shapes:
            pose = Transform.from_pose(shape.origin)
            geometry = shape.geometry
            size = list(geometry.size)
            attributes: dict = {"pos": list(pose.position), "quat": list(pose.quat)}
            if geometry.kind == "mesh":
                assert file is not None, "a mesh shape has its file"
                key = (file, tuple(geometry.scale))
                if key not in meshes:
                    meshes[key] = f"mesh{len(meshes)}"
                    spec.add_mesh(name=meshes[key], file=file, scale=list(geometry.scale))
                attributes.update(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=meshes[key])
            elif geometry.kind == "box":
                attributes.update(type=mujoco.mjtGeom.mjGEOM_BOX, size=[s / 2 for s in size])
            elif geometry.kind == "sphere":
                attributes.update(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[size[0], 0, 0])
            else:  # cylinder, capsule: radius and length, MuJoCo's radius and half length
                kind = mujoco.mjtGeom.mjGEOM_CAPSULE
                if geometry.kind == "cylinder":
                    kind = mujoco.mjtGeom.mjGEOM_CYLINDER
                attributes.update(type=kind, size=[size[0], size[1] / 2, 0])
            body.add_geom(density=density, **attributes)
    model = spec.compile()
    found: dict[str, tuple[float, Vec3, Tensor]] = {}
    for link, name in names:
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
        flat = np.zeros(9)
        mujoco.mju_quat2Mat(flat, model.body_iquat[body])
        rotation = flat.reshape(3, 3)
        tensor = rotation @ np.diag(model.body_inertia[body]) @ rotation.T
        tensor = 0.5 * (tensor + tensor.T)
        ipos = [float(v) for v in model.body_ipos[body]]
        t = [[float(v) for v in row] for row in tensor]
        found[link] = (
            float(model.body_mass[body]),
            (ipos[0], ipos[1], ipos[2]),
            (t[0][0], t[0][1], t[0][2], t[1][1], t[1][2], t[2][2]),
        )
    return found
