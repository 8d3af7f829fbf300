"""The MJCF counterparts of a URDF's Gazebo sensors, on sites at their link and ``<pose>``.

- imu, force_torque and magnetometer become the MJCF sensors mujoco_ros2_control reads an
  ``imu``, ``fts`` or ``magnetometer`` sensor from, named as it looks them up
  (``<name>_quat``, ``_gyro``, ``_accel``; ``<name>_force``, ``_torque``; ``<name>``);
- camera and depth cameras become a ``<camera>`` with the vertical field of view of the
  horizontal one and the image size; Gazebo cameras look along +x of their frame (+z up),
  MuJoCo's along -z (+y up);
- ray and lidar sensors become a fan of rangefinders, as the ``lidars`` input makes them;
- contact sensors become a ``<contact>`` sensor on the link's body.

A ros2_control sensor that describes the same sensor (its name, or its frame and kind) wins:
the sensor is written once, under the name ros2_control expects. An element the model already
has by that name (from the user's MuJoCo inputs) is kept. Kinds MuJoCo does not model are
warned about, one line per kind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lxml import etree

from mjcfbuild.inputs.apply import (
    LinkPlace,
    add_lidar_sites,
    body_element,
    input_error,
    insert_in_body,
    model_section,
    set_pose,
)
from mjcfbuild.inputs.frames import camera_pose
from mjcfbuild.inputs.gazebo import GazeboSensor
from mjcfbuild.inputs.ros2_control import (
    ControlSensor,
    Ros2Control,
    expected_sensors,
    sensor_frame,
)
from mjcfbuild.numbers import output
from mjcfbuild.sources.packages import did_you_mean
from mjcfbuild.urdf.model import Pose, Robot
from mjcfbuild.urdf.transforms import Transform, matrix3, vec3

# The mujoco_type ros2_control gives each kind read through MJCF sensors.
RUNTIME_TYPES = {"imu": "imu", "force_torque": "fts", "magnetometer": "magnetometer"}
_FAMILIES = {"camera": "camera", "depth": "camera", "lidar": "lidar"}
# A Gazebo camera frame (+x forward, +z up) turned into a ROS optical frame (+z forward,
# +y down): optical x = -y, optical y = -z, optical z = +x.
GAZEBO_TO_OPTICAL = Transform(matrix3(((0.0, 0.0, 1.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0))))


@dataclass
class GazeboResult:
    """What writing the Gazebo sensors made: the cameras and lidar rangefinders by name (the
    ros2_control sensor check matches them), and the warnings."""

    cameras: list[str] = field(default_factory=list)
    lidars: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)


def add_gazebo_sensors(
    root: etree._Element,
    sensors: list[GazeboSensor],
    control: Ros2Control,
    links: dict[str, LinkPlace],
    robot: Robot,
) -> GazeboResult:
    """Write the MJCF counterpart of each Gazebo sensor MuJoCo can model into the model tree
    ``root``; :class:`InputError` for one whose reference is no link or joint."""
    result = GazeboResult()
    skipped: dict[str, list[str]] = {}
    fused: list[str] = []  # force-torque and contact sensors on a link fused into its parent
    children = {joint.name: joint.child for joint in robot.joints}
    seen: dict[str, str] = {}  # each modelled Gazebo sensor's name -> its origin
    # Gazebo cameras (lidars) per link: a ros2_control sensor at the link names only a lone one.
    per_link: dict[tuple[str, str], int] = {}
    for sensor in sensors:
        family = _FAMILIES.get(sensor.kind or "")
        if family:
            key = (children.get(sensor.reference, sensor.reference), family)
            per_link[key] = per_link.get(key, 0) + 1
    for sensor in sensors:
        if sensor.kind is None:
            skipped.setdefault(sensor.type or "(no type)", []).append(sensor.name)
            continue
        link = children.get(sensor.reference, sensor.reference)
        if link not in links:
            closest = did_you_mean(sensor.reference, set(links) | set(children))
            raise input_error(
                sensor.origin,
                f"Gazebo sensor '{sensor.name}' is on '{sensor.reference}', which is not a link "
                f"(or joint) of the URDF{closest}",
                hint="set <gazebo reference> to the link the sensor is mounted on",
            )
        if sensor.name in seen:
            result.warnings.append(
                f"{sensor.origin}: Gazebo sensor '{sensor.name}' has the name of the one at "
                f"{seen[sensor.name]}, so only that one is written; rename one"
            )
            continue
        seen[sensor.name] = sensor.origin
        place = links[link]
        pose = LinkPlace(
            place.body,
            place.pose.compose(
                Transform.from_pose(Pose(vec3(sensor.pose[:3]), vec3(sensor.pose[3:])))
            ),
        )
        if sensor.kind in ("force_torque", "contact") and place.body != link:
            fused.append(f"{sensor.name} (on {place.body or 'the world'})")
        if sensor.kind in RUNTIME_TYPES:
            _runtime_sensors(root, sensor, link, pose, control)
        elif sensor.kind in ("camera", "depth"):
            alone = per_link[(link, "camera")] == 1
            name = _device_name(sensor, link, control, "camera", alone)
            if _camera(root, sensor, name, pose):
                result.cameras.append(name)
        elif sensor.kind == "lidar":
            alone = per_link[(link, "lidar")] == 1
            name = _device_name(sensor, link, control, "lidar", alone)
            if _lidar(root, sensor, name, pose):
                result.lidars.append(name)
        else:
            _contact(root, sensor, pose)
    for kind, names in sorted(skipped.items()):
        count = len(names)
        shown = ", ".join(names[:8]) + (", ..." if count > 8 else "")
        result.warnings.append(
            f"{count} Gazebo sensor{'s' if count > 1 else ''} of kind {kind} "
            f"{'are' if count > 1 else 'is'} not modelled: {shown}"
        )
    if fused:
        result.warnings.append(
            f"{len(fused)} Gazebo force_torque or contact sensor{'s' if len(fused) > 1 else ''} "
            f"on links fused into their parent body measure that body's joint or contacts: "
            f"{', '.join(fused[:8])}{', ...' if len(fused) > 8 else ''}; set options.fuse_static: "
            "false to keep each link a body of its own, welded where its fixed joint is"
        )
    return result


def _describes(control: ControlSensor, sensor: GazeboSensor, link: str) -> bool:
    """Whether a ros2_control sensor is the same device as a Gazebo sensor at ``link``."""
    return control.name == sensor.name or sensor_frame(control) in (link, sensor.reference)


def _runtime_sensors(
    root: etree._Element,
    sensor: GazeboSensor,
    link: str,
    place: LinkPlace,
    control: Ros2Control,
) -> None:
    """The MJCF sensors mujoco_ros2_control reads this kind from, unless a ros2_control
    sensor of the same kind describes it (its own are written for it)."""
    kind = RUNTIME_TYPES[sensor.kind or ""]
    for other in control.sensors:
        if other.params.get("mujoco_type") == kind and _describes(other, sensor, link):
            return
    stand_in = ControlSensor(sensor.name, {"mujoco_type": kind}, sensor.origin)
    existing = _names(root, "sensor")
    wanted = [e for e in expected_sensors(stand_in) if e.name not in existing]
    if not wanted:
        return
    site = _site(root, sensor.name, place)
    section = model_section(root, "sensor")
    for expected in wanted:
        attributes = (
            {"name": expected.name, "objtype": "site", "objname": site}
            if expected.tag in ("framequat", "framepos")
            else {"name": expected.name, "site": site}
        )
        etree.SubElement(section, expected.tag, attributes)


def _device_name(
    sensor: GazeboSensor, link: str, control: Ros2Control, kind: str, alone: bool
) -> str:
    """The name ros2_control looks a camera or lidar up by: the one ros2_control sensor of
    that kind at its link (where it is the link's only Gazebo sensor of the kind), else the
    Gazebo sensor's name."""
    matches = [s.name for s in control.sensors if s.kind == kind and _describes(s, sensor, link)]
    if sensor.name in matches or len(matches) != 1 or not alone:
        return sensor.name
    return matches[0]


def vertical_fov(horizontal: float, width: float, height: float) -> float:
    """MuJoCo's ``fovy`` (degrees) for a horizontal field of view (rad) and an image size."""
    return math.degrees(2 * math.atan(math.tan(horizontal / 2) * height / width))


def _camera(root: etree._Element, sensor: GazeboSensor, name: str, place: LinkPlace) -> bool:
    if name in _names(root, "camera"):
        return False  # the user's camera of that name
    element = etree.Element("camera", {"name": name})
    set_pose(element, camera_pose(place.pose.compose(GAZEBO_TO_OPTICAL)))
    values = sensor.values
    width, height = values.get("width", 320.0), values.get("height", 240.0)
    # Gazebo's default field of view is 1.047 rad and its default image 320 x 240.
    element.set("fovy", output(vertical_fov(values.get("horizontal_fov", 1.047), width, height)))
    element.set("resolution", f"{round(width)} {round(height)}")
    insert_in_body(body_element(root, place.body), element)
    return True


def _lidar(root: etree._Element, sensor: GazeboSensor, name: str, place: LinkPlace) -> bool:
    if name in _names(root, "sensor"):
        return False
    values = sensor.values
    samples = max(1, round(values.get("samples", 1)))
    low, high = values.get("min_angle", 0.0), values.get("max_angle", 0.0)
    increment = (high - low) / (samples - 1) if samples > 1 and high > low else 1.0
    high = low if increment == 1.0 else high
    add_lidar_sites(root, place, f"{name}_lidar_body", name, (low, high, increment))
    attributes = {"name": name, "site": name}
    if "range_max" in values:
        attributes["cutoff"] = output(values["range_max"])
    etree.SubElement(model_section(root, "sensor"), "rangefinder", attributes)
    return True


def _contact(root: etree._Element, sensor: GazeboSensor, place: LinkPlace) -> None:
    if sensor.name in _names(root, "sensor") or place.body is None:
        return
    etree.SubElement(
        model_section(root, "sensor"),
        "contact",
        {"name": sensor.name, "body1": place.body, "data": "found force torque"},
    )


def _site(root: etree._Element, name: str, place: LinkPlace) -> str:
    """A new site at ``place`` named ``name`` (made unique)."""
    sites = _names(root, "site")
    while name in sites:
        name += "_site"
    element = etree.Element("site", {"name": name})
    set_pose(element, place.pose)
    insert_in_body(body_element(root, place.body), element)
    return name


def _names(root: etree._Element, tag: str) -> set[str]:
    if tag == "sensor":
        section = root.find("sensor")
        return {e.get("name") or "" for e in section} if section is not None else set()
    return {e.get("name") or "" for e in root.iter(tag)}
