"""Gazebo sensors of a URDF: ``<gazebo reference="link"><sensor type="...">``.

Only what the MJCF counterparts need is read (the SDF pose, a camera's field of view and
image size, a lidar's horizontal scan and range); what MuJoCo does not model (update rates,
noise, clipping, a vertical scan) is kept as text for the report.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

from lxml import etree

# Gazebo sensor types (Gazebo classic and gz sim spellings) -> what the build makes of them.
KINDS = {
    "imu": "imu",
    "force_torque": "force_torque",
    "camera": "camera",
    "depth": "depth",
    "depth_camera": "depth",
    "rgbd_camera": "depth",
    "ray": "lidar",
    "gpu_ray": "lidar",
    "lidar": "lidar",
    "gpu_lidar": "lidar",
    "magnetometer": "magnetometer",
    "contact": "contact",
}


@dataclass
class GazeboSensor:
    """A Gazebo sensor: its name, type, the link (or joint) it references, its SDF pose
    (x y z roll pitch yaw in that frame) and the values its MJCF counterpart needs."""

    name: str
    type: str  # as written: imu, camera, gpu_lidar, gps, ...
    reference: str
    pose: list[float]
    values: dict[str, float]
    not_modelled: list[str]
    origin: str
    collisions: list[str] = field(default_factory=list)  # a contact sensor's <collision>s

    @property
    def kind(self) -> str | None:
        """imu, force_torque, camera, depth, lidar, magnetometer or contact; None for a
        type MuJoCo cannot model."""
        return KINDS.get(self.type)

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)


def read_gazebo_sensors(root: etree._Element, label: str) -> list[GazeboSensor]:
    """Every ``<sensor>`` under a top-level ``<gazebo reference>`` of a parsed URDF."""
    found = []
    for gazebo in root.findall("gazebo"):
        reference = (gazebo.get("reference") or "").strip()
        for sensor in gazebo.findall("sensor"):
            kind = (sensor.get("type") or "").strip()
            name = (sensor.get("name") or "").strip() or f"{reference}_{kind}"
            found.append(
                GazeboSensor(
                    name,
                    kind,
                    reference,
                    _pose(sensor, label),
                    _values(sensor),
                    _not_modelled(sensor),
                    f"{label}:{sensor.sourceline}",
                    [(c.text or "").strip() for c in sensor.iterfind("contact/collision")],
                )
            )
    return found


def _pose(sensor: etree._Element, label: str) -> list[float]:
    element = sensor.find("pose")
    text = (element.text or "").split() if element is not None else []
    if not text:
        return [0.0] * 6
    try:
        values = [float(v) for v in text]
    except ValueError:
        values = []
    if len(values) != 6:
        from mjcfbuild.errors import InputError

        raise InputError(
            f"Gazebo sensor '{sensor.get('name')}': <pose> '{element.text}' is not six numbers",
            file=label,
            line=element.sourceline,
            hint="write x y z roll pitch yaw",
        )
    return values


# Where each value is, below the sensor (the first path found wins).
_PATHS = {
    "horizontal_fov": ("camera/horizontal_fov",),
    "width": ("camera/image/width",),
    "height": ("camera/image/height",),
    "samples": ("ray/scan/horizontal/samples", "lidar/scan/horizontal/samples"),
    "min_angle": ("ray/scan/horizontal/min_angle", "lidar/scan/horizontal/min_angle"),
    "max_angle": ("ray/scan/horizontal/max_angle", "lidar/scan/horizontal/max_angle"),
    "range_min": ("ray/range/min", "lidar/range/min"),
    "range_max": ("ray/range/max", "lidar/range/max"),
    "vertical_samples": ("ray/scan/vertical/samples", "lidar/scan/vertical/samples"),
}


def _values(sensor: etree._Element) -> dict[str, float]:
    values = {}
    for key, paths in _PATHS.items():
        for path in paths:
            element = sensor.find(path)
            if element is None:
                continue
            try:
                values[key] = float((element.text or "").strip())
            except ValueError:
                continue
            break
    return values


def _not_modelled(sensor: etree._Element) -> list[str]:
    """What the sensor says that its MJCF counterpart does not do."""
    notes = []
    rate = sensor.find("update_rate")
    if rate is not None and (rate.text or "").strip():
        notes.append(f"update_rate {(rate.text or '').strip()} Hz")
    if any(True for _ in sensor.iter("noise")):
        notes.append("noise")
    clip = sensor.find("camera/clip")
    if clip is not None:
        notes.append("camera clip (MuJoCo's near and far planes are the model's)")
    for path in ("ray/range/min", "lidar/range/min"):
        element = sensor.find(path)
        if element is not None:
            notes.append(f"range min {(element.text or '').strip()} m")
    for path in ("ray/scan/vertical/samples", "lidar/scan/vertical/samples"):
        element = sensor.find(path)
        if element is not None and (element.text or "").strip() not in ("", "1"):
            notes.append(f"vertical scan of {(element.text or '').strip()} samples (one plane)")
    return notes


def urdf_sensor_warnings(
    root: etree._Element, label: str, gazebo: list[GazeboSensor], described: set[str]
) -> list[str]:
    """One warning per kind of the URDF's own top-level ``<sensor>`` elements (the URDF sensor
    spec: iCub's accelerometers, gyroscopes and force-torque sensors) that no MJCF sensor is
    made for: those a modelled Gazebo sensor, or a ros2_control sensor in ``described``,
    describes under the same name are made from that one."""
    covered = {sensor.name for sensor in gazebo if sensor.kind is not None} | described
    by_kind: dict[str, list[etree._Element]] = {}
    for sensor in root.findall("sensor"):
        if (sensor.get("name") or "").strip() not in covered:
            by_kind.setdefault((sensor.get("type") or "").strip() or "(no type)", []).append(sensor)
    warnings = []
    for kind, sensors in sorted(by_kind.items()):
        count = len(sensors)
        names = [(s.get("name") or "").strip() or f"line {s.sourceline}" for s in sensors]
        shown = ", ".join(names[:8]) + (", ..." if count > 8 else "")
        many = count > 1
        warnings.append(
            f"{label}:{sensors[0].sourceline}: {count} URDF <sensor> element{'s' if many else ''} "
            f"of kind {kind} {'are' if many else 'is'} not modelled: {shown} (MuJoCo sensors are "
            "made from Gazebo sensors, <gazebo reference><sensor>, and ros2_control sensors; "
            f"describe {'them' if many else 'it'} there or in mujoco_inputs)"
        )
    return warnings
