"""``<ros2_control>``: joints with their interfaces, sensors, and what the model must match.

mujoco_ros2_control finds MuJoCo cameras and rangefinders by the names of ros2_control
sensors. A camera or lidar without a sensor of its name (or the reverse) is almost always a
typo, so the build warns, listing both sides. On request, actuators are generated from the
command interfaces and a ``home`` keyframe from the ``initial_value`` parameters.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

from lxml import etree

CAMERA_PARAMS = {"image_topic", "info_topic", "depth_topic", "camera_info_topic"}
LIDAR_PARAMS = {"laserscan_topic", "angle_increment", "min_angle", "max_angle", "range_max"}


@dataclass
class ControlJoint:
    """A ros2_control joint: its command interfaces and initial position."""

    name: str
    commands: list[str]
    initial: float | None
    origin: str


@dataclass
class ControlSensor:
    """A ros2_control sensor and its parameters."""

    name: str
    params: dict[str, str]
    origin: str

    @property
    def kind(self) -> str | None:
        """'camera' or 'lidar' when its parameters say so."""
        if self.params.get("mujoco_type"):
            return None
        if CAMERA_PARAMS & set(self.params):
            return "camera"
        if LIDAR_PARAMS & set(self.params):
            return "lidar"
        return None


@dataclass
class Ros2Control:
    """Every ``<ros2_control>`` of a URDF, combined."""

    joints: list[ControlJoint] = field(default_factory=list)
    sensors: list[ControlSensor] = field(default_factory=list)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)

    @staticmethod
    def from_dict(data: dict) -> Ros2Control:
        """Rebuild from :meth:`to_dict`."""
        return Ros2Control(
            [ControlJoint(**j) for j in data.get("joints", [])],
            [ControlSensor(**s) for s in data.get("sensors", [])],
        )


def read_ros2_control(root: etree._Element, label: str) -> Ros2Control:
    """The ros2_control joints and sensors of a parsed URDF."""
    result = Ros2Control()
    for block in root.findall("ros2_control"):
        for joint in block.findall("joint"):
            commands = [c.get("name", "") for c in joint.findall("command_interface")]
            initial = None
            for state in joint.findall("state_interface"):
                if state.get("name") == "position":
                    for param in state.findall("param"):
                        if param.get("name") == "initial_value":
                            try:
                                initial = float((param.text or "").strip())
                            except ValueError:
                                initial = None
            result.joints.append(
                ControlJoint(
                    joint.get("name", ""),
                    [c for c in commands if c],
                    initial,
                    f"{label}:{joint.sourceline}",
                )
            )
        for sensor in block.findall("sensor"):
            params = {p.get("name", ""): (p.text or "").strip() for p in sensor.findall("param")}
            result.sensors.append(
                ControlSensor(sensor.get("name", ""), params, f"{label}:{sensor.sourceline}")
            )
    return result


def sensor_warnings(
    control: Ros2Control, cameras: list[str], lidar_sensors: list[str]
) -> list[str]:
    """Cameras and lidars without a ros2_control sensor of their name, and the reverse."""
    if not control.sensors and not control.joints:
        return []
    names = {sensor.name for sensor in control.sensors}
    listing = ", ".join(sorted(names)) or "none"
    warnings = []
    for camera in cameras:
        if camera not in names:
            warnings.append(
                f"camera '{camera}' has no ros2_control <sensor name='{camera}'> "
                f"(ros2_control sensors: {listing})"
            )
    for lidar in lidar_sensors:
        if lidar not in names:
            warnings.append(
                f"lidar rangefinder '{lidar}' has no ros2_control <sensor name='{lidar}'> "
                f"(ros2_control sensors: {listing})"
            )
    for sensor in control.sensors:
        if sensor.kind == "camera" and sensor.name not in cameras:
            warnings.append(
                f"{sensor.origin}: ros2_control camera sensor '{sensor.name}' has no MuJoCo "
                f"camera of its name (cameras: {', '.join(sorted(cameras)) or 'none'})"
            )
        if sensor.kind == "lidar" and sensor.name not in lidar_sensors:
            warnings.append(
                f"{sensor.origin}: ros2_control lidar sensor '{sensor.name}' has no MuJoCo "
                f"rangefinder of its name (lidar rangefinders: "
                f"{', '.join(sorted(lidar_sensors)) or 'none'})"
            )
    return warnings


def generate_actuators(root, control: Ros2Control, settings: dict, limits: dict) -> list[str]:
    """Add an actuator per command interface to the model tree; notes on what was skipped.

    ``limits`` maps joint names to their URDF ``Limit``. Joints that inputs already drive
    (an actuator naming the joint) are left alone. Names are the joint's name, or
    ``<joint>_<interface>`` when a joint has several command interfaces.
    """
    from lxml import etree

    from mjcfbuild.numbers import output_list

    section = root.find("actuator")
    if section is None:
        section = etree.SubElement(root, "actuator")
    driven = {element.get("joint") for element in section if element.get("joint")}
    taken = {element.get("name") for element in section if element.get("name")}
    notes = []
    for joint in control.joints:
        if not joint.commands:
            continue
        if joint.name in driven:
            notes.append(
                f"joint '{joint.name}' already has an actuator in the inputs; none generated"
            )
            continue
        gains = settings.get("joints", {}).get(joint.name, {})
        limit = limits.get(joint.name)
        for interface in joint.commands:
            name = joint.name if len(joint.commands) == 1 else f"{joint.name}_{interface}"
            if name in taken:
                notes.append(f"an actuator named '{name}' exists already; none generated")
                continue
            attributes = {"name": name, "joint": joint.name}
            if interface == "position":
                tag = "position"
                base = settings.get("position", {})
                kp = gains.get("kp") or base.get("kp")
                dampratio = (
                    gains.get("dampratio")
                    if gains.get("dampratio") is not None
                    else base.get("dampratio")
                )
                if kp:
                    attributes["kp"] = output_list([kp])
                if dampratio is not None:
                    attributes["dampratio"] = output_list([dampratio])
                if (
                    limit is not None
                    and limit.lower is not None
                    and limit.upper is not None
                    and limit.upper > limit.lower
                ):
                    attributes["ctrlrange"] = output_list([limit.lower, limit.upper])
            elif interface == "velocity":
                tag = "velocity"
                kv = gains.get("kv") or settings.get("velocity", {}).get("kv")
                if kv:
                    attributes["kv"] = output_list([kv])
                if limit is not None and limit.velocity:
                    attributes["ctrlrange"] = output_list([-limit.velocity, limit.velocity])
            elif interface == "effort":
                tag = "motor"
                if limit is not None and limit.effort:
                    attributes["ctrlrange"] = output_list([-limit.effort, limit.effort])
            else:
                notes.append(
                    f"joint '{joint.name}': no actuator for command interface '{interface}'"
                )
                continue
            etree.SubElement(section, tag, attributes)
            taken.add(name)
    return notes
