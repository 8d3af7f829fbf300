"""Models are written with 12 significant digits, not MuJoCo's 6."""

from __future__ import annotations

import math

import mujoco

from mjcfbuild.mjcf.precise import precise_xml


def test_numbers_keep_their_precision_and_defaults_are_dropped():
    spec = mujoco.MjSpec()
    spec.compiler.degree = False
    angle = 0.3
    body = spec.worldbody.add_body(
        name="b", pos=[1 / 3, 0, 2.0], quat=[math.cos(angle), 0, math.sin(angle), 0]
    )
    body.add_joint(name="j", axis=[0, 1, 0], range=[-math.pi, math.pi])
    body.add_geom(size=[0.1, 0, 0], pos=[0, 0, 0])
    body.mass = 1 / 7
    body.inertia = [0.1, 0.1, 0.1]
    body.ipos = [0, 0, 0]
    body.explicitinertial = True
    root = precise_xml(spec)
    xml_body = root.find(".//body[@name='b']")
    assert xml_body.get("pos") == "0.333333333333 0 2"
    assert xml_body.get("quat") == f"{math.cos(angle):.12g} 0 {math.sin(angle):.12g} 0"
    assert root.find(".//joint[@name='j']").get("range") == "-3.14159265359 3.14159265359"
    assert root.find(".//inertial").get("mass") == "0.142857142857"
    geom = root.find(".//geom")
    assert "name" not in geom.attrib  # temporary names used for matching are removed
    assert "pos" not in geom.attrib and "quat" not in geom.attrib


def test_an_axis_given_at_any_length_is_written_as_its_unit_axis_at_full_precision():
    """MuJoCo writes the unit axis (6 digits) of a joint given 1 2 7: it kept them, and the
    model's link 2 m out stood 1e-6 from its URDF pose, failing the check."""
    spec = mujoco.MjSpec()
    body = spec.worldbody.add_body(name="b")
    body.add_joint(name="j", axis=[1, 2, 7])
    body.add_geom(size=[0.1, 0, 0])
    axis = precise_xml(spec).find(".//joint[@name='j']").get("axis")
    length = math.sqrt(1 + 4 + 49)
    assert axis == " ".join(f"{v / length:.12g}" for v in (1, 2, 7))
