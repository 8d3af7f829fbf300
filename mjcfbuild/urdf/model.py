"""A URDF robot as plain data: links, joints, shapes and where each came from.

The parser fills it from XML; the planner resolves mesh paths in it; the assembly turns it into
MuJoCo bodies. It round-trips through JSON (``to_dict``/``robot_from_dict``) so a build step in
another process can use it without parsing the URDF again.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

Vec3 = tuple[float, float, float]
RGBA = tuple[float, float, float, float]

SHAPE_KINDS = ("box", "cylinder", "sphere", "capsule", "mesh")
JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
# The link that stands for the ground: MuJoCo's world body, ROS's and Drake's fixed frame.
WORLD = "world"


@dataclass
class Pose:
    """A URDF ``<origin>``: translation, then roll-pitch-yaw about fixed x, y, z axes."""

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)


@dataclass
class Geometry:
    """A URDF ``<geometry>``.

    ``size`` is in URDF terms: box full extents (x, y, z); cylinder and capsule (radius,
    length); sphere (radius,). Meshes have ``uri`` as written, ``path`` once resolved and
    ``mesh_id``, the name of the build's mesh task that converts the file.
    """

    kind: str
    size: tuple[float, ...] = ()
    uri: str | None = None
    path: str | None = None
    scale: Vec3 = (1.0, 1.0, 1.0)
    mesh_id: str | None = None
    line: int | None = None  # of its element (<mesh>, <box>, ...): where to fix what it names


@dataclass
class Material:
    """A URDF ``<material>``: a colour and/or a texture, possibly only a name reference."""

    name: str | None = None
    rgba: RGBA | None = None
    texture: str | None = None
    texture_line: int | None = None  # of its <texture>: where a texture not found is named


@dataclass
class Shape:
    """One ``<visual>`` or ``<collision>`` of a link."""

    role: str
    index: int
    origin: Pose
    geometry: Geometry
    name: str | None = None
    material: Material | None = None
    line: int | None = None


@dataclass
class Inertial:
    """A URDF ``<inertial>``: mass and inertia tensor (ixx, ixy, ixz, iyy, iyz, izz) at origin."""

    origin: Pose
    mass: float
    inertia: tuple[float, float, float, float, float, float]
    line: int | None = None


@dataclass
class Link:
    """A URDF ``<link>``."""

    name: str
    inertial: Inertial | None = None
    visuals: list[Shape] = field(default_factory=list)
    collisions: list[Shape] = field(default_factory=list)
    line: int | None = None

    @property
    def shapes(self) -> list[Shape]:
        """Visuals, then collisions."""
        return [*self.visuals, *self.collisions]


@dataclass
class Limit:
    """A joint's ``<limit>``; absent values are None."""

    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None


@dataclass
class Mimic:
    """``<mimic>``: this joint = multiplier * joint + offset."""

    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass
class Joint:
    """A URDF ``<joint>``."""

    name: str
    kind: str
    parent: str
    child: str
    origin: Pose = field(default_factory=Pose)
    axis: Vec3 = (1.0, 0.0, 0.0)
    limit: Limit | None = None
    damping: float = 0.0
    friction: float = 0.0
    mimic: Mimic | None = None
    line: int | None = None

    @property
    def moves(self) -> bool:
        """Whether the joint has degrees of freedom."""
        return self.kind != "fixed"


@dataclass
class Robot:
    """A parsed URDF robot, links and joints in file order."""

    name: str
    links: list[Link]
    joints: list[Joint]
    source: str = "robot.urdf"
    mujoco_compiler: dict[str, str] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)

    def link(self, name: str) -> Link:
        """The link called ``name``."""
        return self._links_by_name()[name]

    def _links_by_name(self) -> dict[str, Link]:
        return {link.name: link for link in self.links}

    @property
    def root(self) -> str:
        """The one link that is no joint's child."""
        children = {joint.child for joint in self.joints}
        return next(link.name for link in self.links if link.name not in children)

    def parent_joint(self) -> dict[str, Joint]:
        """Each link's parent joint, by child link name."""
        return {joint.child: joint for joint in self.joints}

    def child_joints(self) -> dict[str, list[Joint]]:
        """Each link's child joints in file order, by parent link name."""
        result: dict[str, list[Joint]] = {link.name: [] for link in self.links}
        for joint in self.joints:
            result[joint.parent].append(joint)
        return result

    def to_dict(self) -> dict:
        """A JSON-friendly form of the robot."""
        return asdict(self)


def robot_from_dict(data: dict) -> Robot:
    """Rebuild a :class:`Robot` from :meth:`Robot.to_dict`."""

    def pose(d: dict) -> Pose:
        return Pose(tuple(d["xyz"]), tuple(d["rpy"]))

    def shape(d: dict) -> Shape:
        geometry = dict(d["geometry"])
        geometry["size"] = tuple(geometry["size"])
        geometry["scale"] = tuple(geometry["scale"])
        material = d.get("material")
        if material is not None:
            material = Material(
                material.get("name"),
                tuple(material["rgba"]) if material.get("rgba") is not None else None,
                material.get("texture"),
                material.get("texture_line"),
            )
        return Shape(
            role=d["role"],
            index=d["index"],
            origin=pose(d["origin"]),
            geometry=Geometry(**geometry),
            name=d.get("name"),
            material=material,
            line=d.get("line"),
        )

    links = []
    for d in data["links"]:
        inertial = d.get("inertial")
        if inertial is not None:
            inertial = Inertial(
                pose(inertial["origin"]),
                inertial["mass"],
                tuple(inertial["inertia"]),
                inertial.get("line"),
            )
        links.append(
            Link(
                name=d["name"],
                inertial=inertial,
                visuals=[shape(s) for s in d["visuals"]],
                collisions=[shape(s) for s in d["collisions"]],
                line=d.get("line"),
            )
        )
    joints = []
    for d in data["joints"]:
        joints.append(
            Joint(
                name=d["name"],
                kind=d["kind"],
                parent=d["parent"],
                child=d["child"],
                origin=pose(d["origin"]),
                axis=tuple(d["axis"]),
                limit=Limit(**d["limit"]) if d.get("limit") else None,
                damping=d["damping"],
                friction=d["friction"],
                mimic=Mimic(**d["mimic"]) if d.get("mimic") else None,
                line=d.get("line"),
            )
        )
    return Robot(
        name=data["name"],
        links=links,
        joints=joints,
        source=data.get("source", "robot.urdf"),
        mujoco_compiler=dict(data.get("mujoco_compiler", {})),
        warnings=list(data.get("warnings", [])),
    )
