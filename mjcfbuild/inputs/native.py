"""The ``mujoco_inputs`` of robot.yaml as :class:`Inputs`, with origins in robot.yaml."""

from __future__ import annotations

from lxml import etree

from mjcfbuild.errors import InputError
from mjcfbuild.inputs.model import (
    CameraInput,
    DecomposeInput,
    Inputs,
    LidarInput,
    ModifyInput,
    SceneInput,
)
from mjcfbuild.inputs.xml_inputs import read_raw_sections


def _text(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return " ".join(_text(v) for v in value)
    return str(value)


def native_inputs(settings: dict, manifest_label: str) -> Inputs:
    """Inputs from the plain form of the manifest's ``mujoco_inputs``."""
    where = f"{manifest_label} mujoco_inputs"
    inputs = Inputs()
    if settings.get("raw"):
        inputs.raw = read_raw_sections(_wrap(settings["raw"], f"{where}.raw"), f"{where}.raw")
    for index, camera in enumerate(settings.get("cameras", [])):
        attributes = {k: _text(v) for k, v in camera.get("attributes", {}).items()}
        for key in ("fovy", "mode", "resolution"):
            if camera.get(key) is not None:
                attributes[key] = _text(camera[key])
        inputs.cameras.append(
            CameraInput(camera["name"], camera["link"], attributes, f"{where}.cameras[{index}]")
        )
    for index, lidar in enumerate(settings.get("lidars", [])):
        inputs.lidars.append(
            LidarInput(
                lidar["sensor_name"],
                lidar["link"],
                float(lidar["min_angle"]),
                float(lidar["max_angle"]),
                float(lidar["angle_increment"]),
                f"{where}.lidars[{index}]",
            )
        )
    for index, modify in enumerate(settings.get("modify", [])):
        attributes = {k: _text(v) for k, v in modify["attributes"].items()}
        inputs.modifications.append(
            ModifyInput(
                modify["type"],
                attributes,
                f"{where}.modify[{index}]",
                name=modify.get("name"),
                mesh=modify.get("mesh"),
                geom_class=modify.get("geom_class"),
            )
        )
    for index, decompose in enumerate(settings.get("decompose", [])):
        inputs.decompositions.append(
            DecomposeInput(
                decompose["mesh"], float(decompose["threshold"]), f"{where}.decompose[{index}]"
            )
        )
    return inputs


def native_scene(mjcf: str | None, manifest_label: str) -> SceneInput | None:
    """The manifest's ``scene.mjcf`` block, checked to be well-formed XML."""
    if not mjcf:
        return None
    _wrap(mjcf, f"{manifest_label} scene.mjcf")
    return SceneInput(mjcf, f"{manifest_label} scene.mjcf")


def _wrap(text: str, label: str) -> etree._Element:
    try:
        return etree.fromstring(
            f"<raw_inputs>{text}</raw_inputs>",
            etree.XMLParser(
                resolve_entities=False, no_network=True, load_dtd=False, remove_comments=True
            ),
        )
    except etree.XMLSyntaxError as exc:
        raise InputError(f"malformed XML: {exc.msg}", file=label, line=exc.lineno) from None
