"""How an actuator is written and read back (mjcfbuild.actuators): each kind the build writes
compiles in MuJoCo and reads back as what was written; robot.yaml's settings reach the
choice; the forms for engines without <dcmotor> simulate the same servo."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from lxml import etree

from mjcfbuild.actuators import (
    DCMOTOR,
    POSITION,
    ActuatorChoice,
    ActuatorRecord,
    actuator_attributes,
    actuator_kind,
    actuator_record,
    as_position_servos,
    dcmotor_of,
    for_mujoco3,
    read_actuator,
    resolve_choice,
    servo_gains,
    settle_kind,
)
from mjcfbuild.manifest.simulation import ActuatorRule, ActuatorSettings

ARM = """<mujoco>
  <worldbody>
    <body name="link">
      <joint name="hinge" axis="0 1 0" range="-1 1"/>
      <geom type="capsule" size="0.02 0.1" pos="0 0 0.1" mass="1"/>
    </body>
  </worldbody>
  <actuator/>
</mujoco>
"""
# A drive as control.motors.Drive.to_dict gives it: 12 N m standing still, none at 20 rad/s.
DRIVE = {"voltage": 24.0, "stall_torque": 12.0, "no_load_speed": 20.0, "peak_torque": 15.0}


def _compiled(record: ActuatorRecord):
    """The arm with ``record``'s actuator written the way the build writes it, compiled."""
    root = etree.fromstring(ARM)
    etree.SubElement(root.find("actuator"), record.type, actuator_attributes(record))
    return mujoco.MjModel.from_xml_string(etree.tostring(root, encoding="unicode"))


@pytest.mark.parametrize(
    ("kind", "kp", "kv"),
    [("position", 40.0, 2.5), ("velocity", None, 3.0), ("motor", None, None)],
)
def test_each_kind_is_read_back_as_written(kind, kp, kv):
    record = ActuatorRecord("hinge", "hinge", kind, "default", kp=kp, kv=kv, ctrlrange=[-1, 1])
    model = _compiled(record)
    assert actuator_kind(model, 0) == kind
    assert dcmotor_of(model, 0) is None
    reading = read_actuator(model, 0)  # what the diff compares
    assert (reading.kind, reading.gear, reading.ctrlrange) == (kind, 1.0, [-1.0, 1.0])
    gains = servo_gains(model, 0)
    if kind == "position":
        assert gains == (kp, kv)
    if kind == "velocity":
        assert gains == (kv, kv)  # a velocity servo's gain is its kv
    assert list(model.actuator_ctrlrange[0]) == [-1, 1]


def test_a_dcmotor_servo_reads_back_its_gains_line_and_force_limit():
    record = ActuatorRecord(
        "hinge", "hinge", DCMOTOR, "default", kp=40, kv=2.5, forcerange=[-10, 10], motor=DRIVE
    )
    model = _compiled(record)
    assert actuator_kind(model, 0) == DCMOTOR
    assert servo_gains(model, 0) == (40.0, 2.5)
    assert read_actuator(model, 0).to_dict() == {
        "kind": DCMOTOR,
        "kp": 40.0,
        "kv": 2.5,
        "gear": 1.0,
        "ctrlrange": None,
        "forcerange": [-10.0, 10.0],  # MuJoCo compiles the saturation into it
    }
    motor = dcmotor_of(model, 0)
    assert motor is not None and motor.ki == 0 and motor.voltage_clamp == 24.0
    # The torque-speed line MuJoCo derived from the nominal point is the drive's.
    assert motor.stall_torque == pytest.approx(12.0, rel=1e-9)
    assert motor.no_load_speed == pytest.approx(20.0, rel=1e-9)
    data = mujoco.MjData(model)
    data.ctrl[0] = 1.0  # far from the joint: the servo asks for more than the drive gives
    mujoco.mj_forward(model, data)
    assert data.actuator_force[0] == pytest.approx(10.0)  # saturation: the force limit


def test_a_position_servo_with_a_speed_line_is_a_dcmotor_unless_ros2_control_commands_it():
    free = ActuatorRecord("a", "a", POSITION, "default", motor=DRIVE)
    settle_kind(free, runtime_commanded=False)
    assert free.type == DCMOTOR and free.motor == DRIVE
    commanded = ActuatorRecord("a", "a", POSITION, "ros2_control", motor=DRIVE)
    settle_kind(commanded, runtime_commanded=True)
    assert commanded.type == POSITION
    assert commanded.motor is not None and commanded.motor["no_load_speed"] is None
    plain = ActuatorRecord("a", "a", POSITION, "default", motor={**DRIVE, "no_load_speed": None})
    settle_kind(plain, runtime_commanded=False)
    assert plain.type == POSITION


def test_a_rule_sets_what_it_names_and_the_defaults_the_rest():
    settings = ActuatorSettings(
        frequency=5,
        speed_limits=False,
        rules=[ActuatorRule(joints=["knee"], kp=80, forcerange=(-3, 3), armature=0.01)],
    )
    chosen = resolve_choice("knee", POSITION, "rule", settings, 0, settings.rules[0], (-9, 9), 4)
    assert (chosen.kp, chosen.frequency, chosen.forcerange) == (80, 5, (-3, 3))
    assert chosen.rule_forcerange and not chosen.effort_limited and not chosen.stiffen
    assert (chosen.armature, chosen.rule, chosen.speed_limit) == (0.01, 0, None)
    default = resolve_choice("hip", POSITION, "default", ActuatorSettings(), None, None, None, 4)
    assert default.frequency == 10 and default.speed_limit == 4 and default.forcerange is None
    record = actuator_record(ActuatorChoice("knee", "motor", "rule", forcerange=(-3, 3)), "k")
    assert (record.name, record.joint, record.forcerange) == ("k", "knee", [-3, 3])


def test_the_mjx_form_of_a_dcmotor_servo_is_a_position_servo_with_its_gains():
    record = ActuatorRecord(
        "hinge", "hinge", DCMOTOR, "default", kp=40, kv=2.5, forcerange=[-10, 10], motor=DRIVE
    )
    root = etree.fromstring(ARM)
    etree.SubElement(root.find("actuator"), DCMOTOR, actuator_attributes(record))
    # An integral term: no <position> servo is the same drive, so it stays.
    integral = {**actuator_attributes(record), "name": "pi", "controller": "40 1 2.5 0 0 24"}
    etree.SubElement(root.find("actuator"), DCMOTOR, integral)
    spec = mujoco.MjSpec.from_string(etree.tostring(root, encoding="unicode"))
    assert as_position_servos(spec) == (1, ["pi"])
    model = spec.compile()
    assert actuator_kind(model, 0) == POSITION and servo_gains(model, 0) == (40.0, 2.5)
    assert list(model.actuator_forcerange[0]) == [-10, 10]
    assert actuator_kind(model, 1) == DCMOTOR


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
