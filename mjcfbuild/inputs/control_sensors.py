"""The MJCF sensors mujoco_ros2_control reads a ``<ros2_control>`` ``<sensor>`` from.

A ros2_control sensor with a ``mujoco_type`` (imu, fts, pose, magnetometer) is read by the
runtime from MJCF sensors it finds by name (:func:`~mjcfbuild.inputs.ros2_control.
expected_sensors`). The build writes each one that the model does not have yet (a sensor of
that name from the user's MuJoCo inputs wins), on a site at the sensor's frame: its
``frame_name`` parameter, else the link of its name. The site is the link's own site where it
has one, else a new site named after the sensor.
"""

from __future__ import annotations

from lxml import etree

from mjcfbuild.inputs.apply import (
    LinkPlace,
    body_element,
    insert_in_body,
    model_section,
    set_pose,
)
from mjcfbuild.inputs.model import origin_location
from mjcfbuild.inputs.ros2_control import (
    ControlSensor,
    Ros2Control,
    expected_sensors,
    runtime_sensor_name,
    sensor_frame,
)
from mjcfbuild.sources.packages import did_you_mean

# Sensors that name their object with objtype/objname rather than site.
_FRAME_SENSORS = {"framequat", "framepos"}


def add_control_sensors(
    root: etree._Element, control: Ros2Control, links: dict[str, LinkPlace]
) -> None:
    """Write the MJCF sensors the runtime looks up for ``control``'s sensors into the model
    tree ``root`` (the check's mujoco_ros2_control section lists them)."""
    existing = {element.get("name") for element in _sensor_section(root, create=False)}
    for sensor in control.sensors:
        wanted = [e for e in expected_sensors(sensor) if e.name not in existing]
        if not wanted:
            continue
        site = _site_at_frame(root, sensor, links)
        section = _sensor_section(root, create=True)
        for expected in wanted:
            attributes = (
                {"name": expected.name, "objtype": "site", "objname": site}
                if expected.tag in _FRAME_SENSORS
                else {"name": expected.name, "site": site}
            )
            etree.SubElement(section, expected.tag, attributes)
            existing.add(expected.name)


def _site_at_frame(root: etree._Element, sensor: ControlSensor, links: dict[str, LinkPlace]):
    """The name of a site at the sensor's frame: the link's own site, else a new one."""
    frame = sensor_frame(sensor)
    if frame not in links:
        from mjcfbuild.errors import InputError

        file, line = origin_location(sensor.origin)
        given = "its frame_name" if sensor.params.get("frame_name") else "its name"
        raise InputError(
            f"ros2_control sensor '{sensor.name}': {given} '{frame}' is not a link of the "
            f"URDF, so the build cannot place its MJCF sensors{did_you_mean(frame, set(links))}",
            file=file,
            line=line,
            hint='set <param name="frame_name"> to the link it measures at',
        )
    place = links[frame]
    body = body_element(root, place.body)
    sites = {element.get("name"): element for element in root.iter("site")}
    own = sites.get(frame)
    if own is not None and own.getparent() is body:
        return frame  # the link's own site (link_sites), at the link's frame
    name = runtime_sensor_name(sensor)
    while name in sites:
        name += "_site"
    element = etree.Element("site", {"name": name})
    set_pose(element, place.pose)
    insert_in_body(body, element)
    return name


def _sensor_section(root: etree._Element, create: bool) -> etree._Element:
    section = root.find("sensor")
    if section is None:
        return model_section(root, "sensor") if create else etree.Element("sensor")
    return section
