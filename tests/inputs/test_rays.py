"""A lidar's replicated rays written out one by one compile to the same MuJoCo model."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from lxml import etree

from mjcfbuild.inputs.apply import LinkPlace, add_lidar_sites
from mjcfbuild.inputs.rays import unroll_lidar_rays
from mjcfbuild.urdf.transforms import Transform

MODEL = """<mujoco><compiler angle="radian"/><worldbody>
<body name="base"><freejoint/><geom size="0.1"/><site name="imu"/>
<body name="head" pos="0.2 0 0.3" euler="0.1 0.2 0.3"><geom size="0.05"/></body></body>
</worldbody><sensor>
<accelerometer name="acc" site="imu"/>
<rangefinder name="scan" site="scan" cutoff="10"/>
<gyro name="gyro" site="imu"/>
<framepos objtype="site" objname="scan"/>
<rangefinder name="tilt" site="tilt"/>
</sensor></mujoco>"""


def lidar_tree(scan_rays: int) -> etree._Element:
    """The model with two lidars, ``scan`` (``scan_rays`` rays) and ``tilt`` (3 rays)."""
    root = etree.fromstring(MODEL)
    head = LinkPlace("head", Transform())
    step = 0.5 / max(scan_rays - 1, 1)
    high = -0.25 + step * (scan_rays - 1)
    assert add_lidar_sites(root, head, "scan_body", "scan", (-0.25, high, step)) == scan_rays
    base = LinkPlace("base", Transform())
    assert add_lidar_sites(root, base, "tilt_body", "tilt", (0.0, 0.2, 0.1)) == 3
    return root


def compiled(root: etree._Element):
    model = mujoco.MjModel.from_xml_string(etree.tostring(root, encoding="unicode"))
    data = mujoco.MjData(model)
    data.qpos[3:7] = [0.9, 0.1, 0.3, -0.2]
    data.qpos[3:7] /= np.linalg.norm(data.qpos[3:7])
    mujoco.mj_forward(model, data)
    return model, data


@pytest.mark.parametrize("rays", [1, 9, 10, 25, 101])
def test_written_out_rays_compile_to_the_replicated_model(rays):
    replicated = lidar_tree(rays)
    written = lidar_tree(rays)
    unroll_lidar_rays(written)
    assert not list(written.iter("replicate"))
    (model, data), (ours, our_data) = compiled(replicated), compiled(written)
    assert ours.nsite == model.nsite == 1 + rays + 3
    names = [[m.site(i).name for i in range(m.nsite)] for m in (model, ours)]
    assert names[0] == names[1]
    assert names[1][1] == "scan-" + "0" * len(str(rays))  # MuJoCo pads to the count's digits
    assert np.abs(our_data.site_xpos - data.site_xpos).max() < 1e-12
    assert np.abs(our_data.site_xmat - data.site_xmat).max() < 1e-12
    assert ours.nsensor == model.nsensor == 2 + 2 * rays + 3
    for index in range(model.nsensor):  # names, order, kind, site and data all agree
        assert ours.sensor(index).name == model.sensor(index).name
        assert ours.sensor_type[index] == model.sensor_type[index]
        assert ours.sensor_objid[index] == model.sensor_objid[index]
        assert ours.sensor_cutoff[index] == model.sensor_cutoff[index]
    assert np.abs(our_data.sensordata - data.sensordata).max() < 1e-12


def test_a_replicate_the_lidar_did_not_write_is_left_to_mujoco():
    root = lidar_tree(5)
    own = etree.fromstring(
        '<replicate count="4" sep="_" offset="0.1 0 0" euler="0 0 0.3"><site name="r"/></replicate>'
    )
    root.find("worldbody/body").append(own)
    named = etree.SubElement(root, "tendon")
    etree.SubElement(etree.SubElement(named, "spatial", {"name": "t"}), "site", {"site": "tilt"})
    unroll_lidar_rays(root)
    # the user's replicate stays, and so does the lidar whose site a tendon names
    assert [r.find("site").get("name") for r in root.iter("replicate")] == ["tilt", "r"]
    assert [s.get("name") for s in root.iter("site") if s.get("name", "").startswith("scan")] == [
        f"scan-{index}" for index in range(5)
    ]


@pytest.mark.parametrize(
    "reference",
    [
        '<sensor><framepos objtype="body" objname="head" reftype="site" refname="scan"/></sensor>',
        '<actuator><motor site="imu" refsite="scan" gear="1 0 0 0 0 0"/></actuator>',
    ],
    ids=["a sensor's refname", "an actuator's refsite"],
)
def test_a_lidar_whose_site_something_else_names_is_left_to_mujoco(reference):
    root = lidar_tree(3)
    addition = etree.fromstring(reference)
    existing = root.find(addition.tag)
    if existing is None:
        root.append(addition)
    else:
        existing.extend(list(addition))
    unroll_lidar_rays(root)
    # MuJoCo's replicate resolves the name; written-out rays would leave it dangling
    assert [r.find("site").get("name") for r in root.iter("replicate")] == ["scan"]
    compiled(root)  # MuJoCo takes it
