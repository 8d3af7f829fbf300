"""The scene file: the robot on a floor under a light and a sky (Menagerie style), or the
robot with a user's ``<scene>`` block."""

from __future__ import annotations

from mjcfbuild.markup import xml_attribute

_SCENE = """<mujoco model={model}>
  <include file={robot}/>

  <visual>
    <headlight diffuse="0.6 0.6 0.6" ambient="0.3 0.3 0.3" specular="0 0 0"/>
    <rgba haze="0.15 0.25 0.35 1"/>
    <global azimuth="120" elevation="-20"/>
  </visual>

  <asset>
    <texture type="skybox" builtin="gradient" rgb1="0.3 0.5 0.7" rgb2="0 0 0"
      width="512" height="3072"/>
    <texture type="2d" name="groundplane" builtin="checker" mark="edge"
      rgb1="0.2 0.3 0.4" rgb2="0.1 0.2 0.3" markrgb="0.8 0.8 0.8" width="300" height="300"/>
    <material name="groundplane" texture="groundplane" texuniform="true" texrepeat="5 5"
      reflectance="0.2"/>
  </asset>

  <worldbody>
    <light pos="0 0 1.5" dir="0 0 -1" directional="true"/>
    <geom name="floor"{floor} size="0 0 0.05" type="plane" material="groundplane"/>
  </worldbody>
</mujoco>
"""


def default_scene(model: str, robot_file: str, floor: float = 0.0) -> str:
    """The scene XML that includes ``robot_file``, with its floor at height ``floor``."""
    from mjcfbuild.numbers import output_list

    where = f' pos="0 0 {output_list([floor])}"' if floor else ""
    return _SCENE.format(
        model=xml_attribute(f"{model} scene"), robot=xml_attribute(robot_file), floor=where
    )


def scene_with(model: str, robot_file: str, block: str, origin: str, floor: float = 0.0) -> bytes:
    """A scene that includes ``robot_file`` and holds the MJCF of a ``<scene>`` block; its
    first plane geom (the floor) is moved to height ``floor``."""
    from lxml import etree

    from mjcfbuild.errors import InputError
    from mjcfbuild.inputs.model import origin_location

    try:
        content = etree.fromstring(f"<scene>{block}</scene>")
    except etree.XMLSyntaxError as exc:
        file, line = origin_location(origin)
        raise InputError(f"malformed scene XML: {exc.msg}", file=file, line=line) from None
    root = etree.Element("mujoco", {"model": f"{model} scene"})
    etree.SubElement(root, "include", {"file": robot_file})
    for child in content:
        if isinstance(child.tag, str):
            root.append(child)
    if floor:
        from mjcfbuild.numbers import output_list

        plane = next((g for g in root.iter("geom") if g.get("type") == "plane"), None)
        if plane is not None:
            position = [float(v) for v in (plane.get("pos") or "0 0 0").split()]
            plane.set("pos", output_list([*position[:2], position[2] + floor]))
    etree.indent(root, space="  ")
    return etree.tostring(root, encoding="unicode").encode() + b"\n"
