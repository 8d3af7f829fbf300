"""The build's simulations run without the model's sensors (:mod:`mjcfbuild.mjsensors`)."""

from __future__ import annotations

import mujoco
import numpy as np

from mjcfbuild.mjsensors import without_sensors


def test_a_simulation_without_sensors_moves_alike_and_casts_no_ray():
    """A lidar unrolled into rangefinders casts every ray each step: TIAGo Pro's 1,639 made
    its check take 53 s. The simulations read no sensor; their results are the same."""

    rays = "".join(f'<rangefinder site="s" name="r{i}"/>' for i in range(50))
    xml = (
        '<mujoco><worldbody><geom type="plane" size="1 1 1"/><body pos="0 0 0.3">'
        '<freejoint/><geom size="0.05"/><site name="s"/></body></worldbody>'
        f"<sensor>{rays}</sensor></mujoco>"
    )
    with_sensors = mujoco.MjModel.from_xml_string(xml)
    without = without_sensors(mujoco.MjModel.from_xml_string(xml))
    poses = []
    for model in (with_sensors, without):
        data = mujoco.MjData(model)
        for _ in range(200):
            mujoco.mj_step(model, data)
        poses.append(data.qpos.copy())
        sensed = data.sensordata.copy()
    assert np.array_equal(poses[0], poses[1])
    assert not sensed.any()  # computed no more: the rays were not cast
