"""The model as the page's MuJoCo (3.14) reads it: what MuJoCo 4.0 writes and 3.14 refuses
taken out, with the simulation unchanged."""

from __future__ import annotations

import numpy as np

from mjcfbuild.mjcf.compat import for_mujoco3

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
    page = for_mujoco3(written)
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
    assert for_mujoco3(xml) == xml
    both = b'<general input="pos" name="a"/><motor name="b" input="pos" gear="2"/>'
    assert for_mujoco3(both) == b'<general name="a"/><motor name="b" gear="2"/>'


def test_a_general_with_dc_motor_dynamics_keeps_its_input():
    """MjSpec writes a <dcmotor> as a <general> with dcmotor gain, bias and dynamics, whose
    controller needs its input: taking it out would make the model fail to load."""
    xml = (
        b'<general name="m" joint="j" dyntype="dcmotor" gaintype="dcmotor" input="pos" '
        b'biastype="dcmotor" gainprm="1.92 0.8 0 0 100 0 5 24"/>'
    )
    assert for_mujoco3(xml) == xml
