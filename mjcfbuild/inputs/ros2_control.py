"""``<ros2_control>``: joints with their interfaces, sensors, and what the model must match.

mujoco_ros2_control finds MuJoCo cameras and rangefinders by the names of ros2_control
sensors. A camera or lidar without a sensor of its name (or the reverse) is almost always a
typo, so the build warns, listing both sides. The command interfaces, ``initial_value``
parameters and ROS 1 transmissions feed the actuators and home pose (see mjcfbuild.control).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields

from lxml import etree

from mjcfbuild.inputs.ros2_control_parser import ParserRefusal, block_refusals

CAMERA_PARAMS = {"image_topic", "info_topic", "depth_topic", "camera_info_topic"}
LIDAR_PARAMS = {"laserscan_topic", "angle_increment", "min_angle", "max_angle", "range_max"}


@dataclass
class ControlJoint:
    """A ros2_control joint: its command interfaces and initial position."""

    name: str
    commands: list[str]
    initial: float | None
    origin: str
    plugin: str = ""  # its block's <hardware> <plugin>: the runtime the block is written for
    mimic: str | None = None  # the joint a ``<param name="mimic">`` makes it follow
    # Whether it has a position state interface: the runtime starts such a joint at its
    # initial_value (0 without one) unless an initial_keyframe is given.
    position_state: bool = True
    block: int = 0  # which <ros2_control> block of the URDF holds it (0 the first)
    # Its mimic="..." attribute ("true", "false" or ""): ros2_control's parser takes a joint with
    # a URDF <mimic> for an activated mimic joint unless it is "false".
    mimic_attribute: str = ""
    # Its state interfaces' names; None in a plan an earlier version wrote, which kept only
    # whether one is position.
    states: list[str] | None = None


@dataclass
class ControlSensor:
    """A ros2_control sensor and its parameters."""

    name: str
    params: dict[str, str]
    origin: str
    # The <hardware> parameters of its block: mujoco_ros2_control reads the MJCF sensor
    # names' suffixes there (force_mjcf_suffix, ...), not from the sensor.
    hardware: dict[str, str] = field(default_factory=dict)
    plugin: str = ""  # its block's <hardware> <plugin>

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
class Transmission:
    """One joint of a ``<transmission>`` (ROS 1's, or ros2_control's own): the hardware
    interfaces that drive it, its reduction, and what else the transmission holds."""

    joint: str
    interfaces: list[str]
    origin: str
    reduction: float | None = None  # mechanicalReduction (ROS 1) or mechanical_reduction
    actuators: list[str] = field(default_factory=list)  # the transmission's <actuator> names
    element: str = ""  # which <transmission> element holds it ("#3": the document's third)
    kind: str = ""  # its type (transmission_interface/SimpleTransmission, a vendor's plugin)
    in_ros2_control: bool = False  # inside a <ros2_control> block, where the runtime reads it
    plugin: str = ""  # that block's <hardware> <plugin>: the runtime it is written for
    block: int = -1  # which <ros2_control> block holds it (-1: a ROS 1 one, outside any)
    # What ros2_control's parser reads for a block's transmission, which its SimpleTransmission
    # applies: the joint's own <mechanical_reduction> and <offset> (signed; 1 and 0 where none is
    # given or it is no number), not the actuator's nor a <param>.
    joint_reduction: float = 1.0
    joint_offset: float = 0.0
    # Its <joint> and <actuator> elements without the role attribute ros2_control's parser
    # requires ("joint 'knee'", "actuator 'm1'").
    roleless: list[str] = field(default_factory=list)
    # A block's transmission without a <plugin> element at all (not an empty one), where
    # ros2_control's parser reads the type from the element it did not find.
    plugin_missing: bool = False

    def commands(self) -> bool:
        """Whether the transmission commands its joint: it names a hardware interface that
        is not a state (read-only) one, or none (ros2_control's transmissions name none)."""
        return not self.interfaces or any(
            not name.endswith("StateInterface") for name in self.interfaces
        )


@dataclass
class BlockElement:
    """A child element of a ``<ros2_control>`` block that a rule judges on its own: one whose
    tag ros2_control's parser does not know, or a ``<transmission>`` without a ``<joint>``."""

    tag: str  # as ros2_control's parser (tinyxml2) names it: "actuator", "xacro:property"
    origin: str
    block: int  # which <ros2_control> block holds it (0 the first)
    plugin: str = ""  # that block's <hardware> <plugin>
    element: str = ""  # a transmission's place in the document ("#3")


# The children ros2_control's parser reads in a <ros2_control> block (parse_resource_from_xml);
# any other element makes it refuse the description.
BLOCK_CHILDREN = ("hardware", "joint", "sensor", "gpio", "transmission")


# The hardware plugins of mujoco_ros2_control (MujocoSystemInterface, and older names) share
# its package's prefix: a <ros2_control> block naming another (a real robot's driver) is not
# run by it as written.
RUNTIME_PLUGINS = "mujoco_ros2_control/"


def runtime_plugin(plugin: str) -> bool:
    """Whether a block of ``plugin`` is written for mujoco_ros2_control (or names none)."""
    return not plugin or plugin.startswith(RUNTIME_PLUGINS)


@dataclass
class Ros2Control:
    """Every ``<ros2_control>`` of a URDF, combined, and its ROS 1 ``<transmission>`` elements."""

    joints: list[ControlJoint] = field(default_factory=list)
    sensors: list[ControlSensor] = field(default_factory=list)
    transmissions: list[Transmission] = field(default_factory=list)
    # The <hardware> <param>s mujoco_ros2_control reads: those of the blocks written for it,
    # or of every block where none is (a description whose driver an argument swaps).
    hardware: dict[str, str] = field(default_factory=dict)
    plugins: list[str] = field(default_factory=list)  # each block's <hardware> <plugin>
    hardware_origins: dict[str, str] = field(default_factory=dict)  # param -> "file:line"
    unknown_children: list[BlockElement] = field(default_factory=list)  # the parser refuses
    jointless: list[BlockElement] = field(default_factory=list)  # block transmissions, no <joint>
    # Elements lacking an attribute or child ros2_control's parser reads (ros2_control_parser)
    refusals: list[ParserRefusal] = field(default_factory=list)

    def runs(self, plugin: str) -> bool:
        """Whether mujoco_ros2_control runs a block of ``plugin``: where some block is
        written for it, only those; where none is, every block (as it would run once the
        plugin is swapped for its own, which descriptions do with a xacro argument)."""
        if any(runtime_plugin(name) for name in self.plugins):
            return runtime_plugin(plugin)
        return True

    def at(self, param: str) -> str:
        """``file:line: `` of the runtime's <hardware> ``param``, where it is known."""
        origin = self.hardware_origins.get(param)
        return f"{origin}: " if origin else ""

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)

    @staticmethod
    def from_dict(data: dict) -> Ros2Control:
        """Rebuild from :meth:`to_dict`."""
        return Ros2Control(
            [_known(ControlJoint, j) for j in data.get("joints", [])],
            [_known(ControlSensor, s) for s in data.get("sensors", [])],
            [_known(Transmission, t) for t in data.get("transmissions", [])],
            dict(data.get("hardware", {})),
            list(data.get("plugins", [])),
            dict(data.get("hardware_origins", {})),
            [_known(BlockElement, e) for e in data.get("unknown_children", [])],
            [_known(BlockElement, e) for e in data.get("jointless", [])],
            [_known(ParserRefusal, r) for r in data.get("refusals", [])],
        )


def _known(kind, data: dict):
    """``kind`` from a record's fields it has: a plan an earlier version wrote (which
    ``mjcfbuild check`` reads as it is) may hold fields since removed."""
    names = {item.name for item in fields(kind)}
    return kind(**{key: value for key, value in data.items() if key in names})


def read_ros2_control(root: etree._Element, label: str) -> Ros2Control:
    """The ros2_control joints and sensors of a parsed URDF."""
    result = Ros2Control()
    blocks = root.findall("ros2_control")
    result.plugins = [(block.findtext("hardware/plugin") or "").strip() for block in blocks]
    for number, (block, plugin) in enumerate(zip(blocks, result.plugins, strict=True)):
        result.refusals += block_refusals(block, label)
        result.unknown_children += [
            BlockElement(_tag_name(child), f"{label}:{child.sourceline}", number, plugin)
            for child in block
            if isinstance(child.tag, str) and child.tag not in BLOCK_CHILDREN
        ]
        declared = [p for element in block.findall("hardware") for p in element.findall("param")]
        hardware = {p.get("name", ""): (p.text or "").strip() for p in declared}
        if result.runs(plugin):
            result.hardware.update(hardware)
            result.hardware_origins.update(
                {p.get("name", ""): f"{label}:{p.sourceline}" for p in declared}
            )
        for joint in block.findall("joint"):
            commands = [c.get("name", "") for c in joint.findall("command_interface")]
            initial = None
            states = [state.get("name", "") for state in joint.findall("state_interface")]
            for state in joint.findall("state_interface"):
                if state.get("name") == "position":
                    for param in state.findall("param"):
                        if param.get("name") == "initial_value":
                            try:
                                initial = float((param.text or "").strip())
                            except ValueError:
                                initial = None
            mimic = next(
                (
                    (p.text or "").strip()
                    for p in joint.findall("param")
                    if p.get("name") == "mimic"
                ),
                None,
            )
            result.joints.append(
                ControlJoint(
                    joint.get("name", ""),
                    [c for c in commands if c],
                    initial,
                    f"{label}:{joint.sourceline}",
                    plugin,
                    mimic or None,
                    "position" in states,
                    number,
                    (joint.get("mimic") or "").strip().lower(),
                    [name for name in states if name],
                )
            )
        for sensor in block.findall("sensor"):
            params = {p.get("name", ""): (p.text or "").strip() for p in sensor.findall("param")}
            result.sensors.append(
                ControlSensor(
                    sensor.get("name", ""),
                    params,
                    f"{label}:{sensor.sourceline}",
                    hardware,
                    plugin,
                )
            )
    # Each element by its place in the document: generated URDFs put many on one line. The
    # list keeps lxml's proxies alive, so findall below returns these same objects.
    order = list(root.iter("transmission"))
    elements = {element: f"#{n}" for n, element in enumerate(order, start=1)}
    for transmission in root.findall("transmission"):
        actuators = _actuators(transmission)
        element = elements[transmission]
        # <type> since ROS Hydro; a type="" attribute before it
        kind = (transmission.findtext("type") or transmission.get("type") or "").strip()
        for joint in transmission.findall("joint"):
            # hardwareInterface sits under <joint> (ROS 1 since Indigo) or under <actuator>.
            interfaces = [
                (element.text or "").strip()
                for element in [
                    *joint.findall("hardwareInterface"),
                    *(
                        a
                        for act in transmission.findall("actuator")
                        for a in act.findall("hardwareInterface")
                    ),
                ]
            ]
            result.transmissions.append(
                Transmission(
                    joint.get("name", ""),
                    [i for i in interfaces if i],
                    f"{label}:{joint.sourceline}",
                    _reduction(transmission, joint),
                    actuators,
                    element,
                    kind,
                )
            )
    # ros2_control's own <transmission> (transmission_interface plugins): no hardware
    # interface, but the joint's mechanical_reduction.
    for number, block in enumerate(root.findall("ros2_control")):
        plugin = (block.findtext("hardware/plugin") or "").strip()
        for transmission in block.findall("transmission"):
            actuators = _actuators(transmission)
            element = elements[transmission]
            kind = (transmission.findtext("plugin") or "").strip()
            if transmission.find("joint") is None:
                where = f"{label}:{transmission.sourceline}"
                result.jointless.append(
                    BlockElement("transmission", where, number, plugin, element)
                )
            roleless = [
                f"{part.tag} '{part.get('name', '')}'"
                for part in [*transmission.findall("joint"), *transmission.findall("actuator")]
                if part.get("role") is None
            ]
            for joint in transmission.findall("joint"):
                result.transmissions.append(
                    Transmission(
                        joint.get("name", ""),
                        [],
                        f"{label}:{joint.sourceline}",
                        _reduction(transmission, joint),
                        actuators,
                        element,
                        kind,
                        in_ros2_control=True,
                        plugin=plugin,
                        block=number,
                        joint_reduction=_parsed_value(joint, "mechanical_reduction", 1.0),
                        joint_offset=_parsed_value(joint, "offset", 0.0),
                        roleless=roleless,
                        plugin_missing=transmission.find("plugin") is None,
                    )
                )
    return result


def _tag_name(element: etree._Element) -> str:
    """An element's name as the XML writes it (``xacro:property``), not lxml's ``{uri}name``."""
    name = etree.QName(element).localname
    return f"{element.prefix}:{name}" if element.prefix else name


def _parsed_value(joint: etree._Element, tag: str, default: float) -> float:
    """A transmission joint's ``<tag>`` as ros2_control's parser reads it
    (get_parameter_value_or): the first child element of that tag with text; ``default``
    where there is none or its text is no number."""
    for child in joint:
        if child.tag == tag and child.text:
            try:
                return float(child.text.strip())
            except ValueError:
                return default
    return default


def transmission_joint_warnings(control: Ros2Control, joints: list[str]) -> list[str]:
    """A warning for each ROS 1 ``<transmission>`` joint the URDF does not have (``joints``:
    the URDF's), at its line, with the closest name: it sets nothing, and MuJoCo's tools, which
    ignore ROS 1 transmissions, would not say so either. (A ros2_control block's transmission
    is the runtime check's: mujoco_ros2_control refuses it at start-up.)"""
    from mjcfbuild.sources.packages import did_you_mean

    known = set(joints)
    return [
        f"{transmission.origin}: <transmission> {transmission.element} names joint "
        f"'{transmission.joint}', which the URDF does not have, so it is ignored"
        f"{did_you_mean(transmission.joint, known)}"
        for transmission in control.transmissions
        if not transmission.in_ros2_control and transmission.joint not in known
    ]


def _actuators(transmission: etree._Element) -> list[str]:
    """The names of a transmission's ``<actuator>`` elements (unnamed ones left out)."""
    return [name for a in transmission.findall("actuator") if (name := a.get("name", ""))]


_REDUCTION_TAGS = ("mechanicalReduction", "mechanical_reduction")


def _reduction(transmission: etree._Element, joint: etree._Element) -> float | None:
    """The gear ratio a transmission gives ``joint``: its own reduction element, else the
    actuator's (ROS 1 puts it there), else a ``<param name="mechanical_reduction">``; None
    where none is given, it is 1 or it is not a number."""
    candidates = [
        *(joint.find(tag) for tag in _REDUCTION_TAGS),
        *(a.find(tag) for a in transmission.findall("actuator") for tag in _REDUCTION_TAGS),
        *(p for p in transmission.iter("param") if p.get("name") in _REDUCTION_TAGS),
    ]
    for element in candidates:
        if element is None:
            continue
        try:
            value = abs(float((element.text or "").strip()))
        except ValueError:
            continue
        # A negative reduction only flips the direction, which the URDF's axis already says;
        # 1, which most descriptions write as a placeholder, is no gearbox.
        if value > 0 and value != 1:
            return value
    return None


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


# mujoco_ros2_control's sensor types (its ``mujoco_type`` parameter) and the MJCF sensors each
# is read from: (what it measures, the <hardware> parameter that replaces the suffix, the
# default suffix, the MJCF sensor element). The names are the sensor's ``mujoco_sensor_name``
# parameter (else the sensor's own name) plus the suffix.
RUNTIME_SENSORS: dict[str, tuple[tuple[str, str | None, str, str], ...]] = {
    "imu": (
        ("orientation", "orientation_mjcf_suffix", "_quat", "framequat"),
        ("angular_velocity", "angular_velocity_mjcf_suffix", "_gyro", "gyro"),
        ("linear_acceleration", "linear_acceleration_mjcf_suffix", "_accel", "accelerometer"),
    ),
    "fts": (
        ("force", "force_mjcf_suffix", "_force", "force"),
        ("torque", "torque_mjcf_suffix", "_torque", "torque"),
    ),
    "pose": (
        ("position", "position_mjcf_suffix", "_pos", "framepos"),
        ("orientation", "orientation_mjcf_suffix", "_quat", "framequat"),
    ),
    "magnetometer": (("magnetic_field", None, "", "magnetometer"),),
}


@dataclass(frozen=True)
class ExpectedSensor:
    """An MJCF sensor mujoco_ros2_control looks up by name for a ros2_control sensor."""

    name: str
    tag: str  # the MJCF element: framequat, gyro, accelerometer, force, torque, ...
    measures: str


def runtime_sensor_name(sensor: ControlSensor) -> str:
    """The name the runtime puts before the suffixes: ``mujoco_sensor_name``, else the
    sensor's own."""
    return sensor.params.get("mujoco_sensor_name") or sensor.name


def expected_sensors(sensor: ControlSensor) -> list[ExpectedSensor]:
    """The MJCF sensors the runtime reads ``sensor`` from (none without a ``mujoco_type``);
    :class:`InputError` for a type it does not know."""
    kind = sensor.params.get("mujoco_type")
    if not kind:
        return []
    if kind not in RUNTIME_SENSORS:
        from mjcfbuild.errors import InputError
        from mjcfbuild.inputs.model import origin_location

        file, line = origin_location(sensor.origin)
        raise InputError(
            f"ros2_control sensor '{sensor.name}' has mujoco_type '{kind}', which "
            "mujoco_ros2_control does not know",
            file=file,
            line=line,
            hint=f"use one of {', '.join(RUNTIME_SENSORS)}",
        )
    base = runtime_sensor_name(sensor)
    return [
        ExpectedSensor(base + sensor.hardware.get(parameter or "", default), tag, measures)
        for measures, parameter, default, tag in RUNTIME_SENSORS[kind]
    ]


def sensor_frame(sensor: ControlSensor) -> str:
    """The URDF link (or frame) a ros2_control sensor measures at: its ``frame_name`` (or
    ``frame_id``) parameter, else the link of its own name."""
    return sensor.params.get("frame_name") or sensor.params.get("frame_id") or sensor.name


# mujoco_ros2_control's actuator kinds, from the actuator's bias (getActuatorType), and since
# its 2026 releases an <intvelocity>'s integrator: its ctrl is a velocity.
def runtime_actuator_kind(
    biastype: int, biasprm: tuple[float, ...], integrated_gain: float | None = None
) -> str:
    """'motor', 'position', 'velocity' or 'custom', as mujoco_ros2_control classifies an
    actuator with bias type ``biastype`` (mjtBias: 0 none, 1 affine) and ``biasprm``;
    ``integrated_gain`` is the fixed gain of an actuator whose ctrl an integrator turns into
    its activation (dyntype integrator), None for others."""
    if (
        integrated_gain is not None
        and biastype == 1
        and biasprm[0] == 0
        and biasprm[1] == -integrated_gain
    ):
        return "velocity"  # an <intvelocity>: kp (act - q), act the integral of ctrl
    if biastype == 0:
        return "motor"
    if biastype == 1 and biasprm[1] != 0:
        return "position"
    if biastype == 1 and biasprm[2] != 0:
        return "velocity"
    return "custom"


def model_actuator_kind(model, actuator: int) -> str:
    """:func:`runtime_actuator_kind` of actuator ``actuator`` of a compiled ``model``."""
    import mujoco

    integrated = model.actuator_dyntype[actuator] == mujoco.mjtDyn.mjDYN_INTEGRATOR
    fixed = model.actuator_gaintype[actuator] == mujoco.mjtGain.mjGAIN_FIXED
    return runtime_actuator_kind(
        int(model.actuator_biastype[actuator]),
        tuple(float(v) for v in model.actuator_biasprm[actuator]),
        float(model.actuator_gainprm[actuator][0]) if integrated and fixed else None,
    )


# The command interfaces each kind takes directly, and those it takes through the runtime's
# PIDs (pid_gains from a pids_config_file); torque and force are effort to the runtime.
_DIRECT = {
    "position": {"position"},
    "velocity": {"velocity"},
    "motor": {"effort"},
    "custom": {"effort"},
}
_WITH_PIDS = {
    "position": set(),
    "velocity": {"position"},
    "motor": {"position", "velocity"},
    "custom": {"position", "velocity"},
}
EFFORT_NAMES = {"effort", "torque", "force"}


def takes_directly(kind: str, interface: str) -> bool:
    """Whether the runtime writes an ``interface`` command straight into the ctrl of an
    actuator of ``kind`` (torque and force are effort to it)."""
    name = "effort" if interface in EFFORT_NAMES else interface
    return name in _DIRECT.get(kind, set())


def needs_pids(kind: str, interface: str) -> bool:
    """Whether the runtime takes ``interface`` on an actuator of ``kind`` only with PID gains:
    without them it stops at start-up ("... not supported with motor or custom actuator
    without defining the PIDs"), where other refusals are an error it logs and goes on."""
    name = "effort" if interface in EFFORT_NAMES else interface
    return name in _WITH_PIDS.get(kind, set())
