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
