"""Where a robot's collision geometry pushes on the floor: curved surfaces at their lowest
points, flat faces over their area (mjcfbuild.control.floor, through the stance that decides
whether a robot can stand without a controller)."""

from __future__ import annotations

import mujoco
import pytest

from mjcfbuild.control.standing import AREA, stance

# A floating body with two feet 0.2 m apart along y, each {foot} (centred 0.4 m under the body).
ROBOT = """<mujoco>
  <worldbody>
    <body name="base" pos="0 0 {height}">
      <freejoint/>
      <geom type="box" size="0.1 0.15 0.05" mass="5"/>
      <body name="left" pos="0 0.1 -0.4"><geom {foot} mass="1"/></body>
      <body name="right" pos="0 -0.1 -0.4"><geom {foot} mass="1"/></body>
    </body>
  </worldbody>
</mujoco>"""


@pytest.mark.parametrize(
    ("foot", "reach", "stands"),
    [
        # Curved feet touch at a point each: two of them make a line, whatever the tolerance.
        ('type="sphere" size="0.03"', 0.03, False),
        ('type="ellipsoid" size="0.05 0.04 0.03"', 0.03, False),
        ('type="capsule" size="0.03 0.05"', 0.08, False),  # standing on an end
        # Lying, a capsule or a cylinder touches along a segment: along the line between the
        # feet the two segments stay on it, across it they span an area.
        ('type="capsule" size="0.03 0.05" euler="90 0 0"', 0.03, False),
        ('type="cylinder" size="0.03 0.05" euler="90 0 0"', 0.03, False),
        ('type="capsule" size="0.03 0.05" euler="0 90 0"', 0.03, True),
        ('type="cylinder" size="0.03 0.05" euler="0 90 0"', 0.03, True),
        # Flat: a cylinder on its cap, a box on its face.
        ('type="cylinder" size="0.03 0.05"', 0.05, True),
        ('type="box" size="0.05 0.03 0.02"', 0.02, True),
    ],
)
def test_curved_feet_touch_the_floor_at_points_and_flat_ones_over_an_area(foot, reach, stands):
    model = mujoco.MjModel.from_xml_string(ROBOT.format(foot=foot, height=0.4 + reach))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    found = stance(model, data)
    assert len(found.feet) == 2
    assert (found.area >= AREA) is stands, found.area
    assert found.can_stand is stands
