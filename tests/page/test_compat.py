"""The model as the page's MuJoCo (3.14) reads it: what MuJoCo 4.0 writes and 3.14 refuses
taken out, with the simulation unchanged."""

from __future__ import annotations

import numpy as np

from mjcfbuild.page.compat import for_wasm

SERVO = """<mujoco>
  <worldbody>
    <body name="link">
      <joint name="hinge" axis="0 1 0" range="-1 1"/>
      <geom type="capsule" size="0.02 0.1" pos="0 0 0.1" mass="1"/>
    </body>
  </worldbody>
  <actuator>
    <position name="servo" joint="hinge" kp="50" dampratio="1" ctrlrange="-1 1"/>
  </actuator>
</mujoco>
"""


def test_the_position_shortcuts_input_goes_and_the_servo_stays_the_same():
    import mujoco

    written = mujoco.MjSpec.from_string(SERVO).to_xml().encode()  # as MuJoCo 4.0 saves it
    assert b'input="pos"' in written
    page = for_wasm(written)
    assert b"input=" not in page
    assert page == written.replace(b' input="pos"', b"")  # nothing else touched
    paths = []
    for xml in (written, page):
        model = mujoco.MjModel.from_xml_string(xml.decode())
        data = mujoco.MjData(model)
        path = []
        for step in range(300):
            data.ctrl[0] = 2 * mujoco.mju_Halton(step, 2) - 1
            mujoco.mj_step(model, data)
            path.append(data.qpos[0])
        paths.append(np.array(path))
    assert np.array_equal(paths[0], paths[1])


def test_the_actuators_that_take_an_input_keep_it():
    xml = b'<actuator><dcmotor name="m" joint="j" input="pos"/><pid input="vel"/></actuator>'
    assert for_wasm(xml) == xml
    both = b'<general input="pos" name="a"/><motor name="b" input="pos" gear="2"/>'
    assert for_wasm(both) == b'<general name="a"/><motor name="b" gear="2"/>'
