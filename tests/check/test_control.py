"""The control checks on hand-written models: Menagerie's pseudorandom-control test names the
joint that ran away and what to change."""

from __future__ import annotations

import mujoco

from mjcfbuild.check.control import check_control, menagerie_test
from mjcfbuild.mjwarnings import capture_mujoco_warnings, take_mujoco_warnings

PENDULUM = """<mujoco>
  <option timestep="0.002" integrator="Euler"/>
  <worldbody>
    <body name="arm">
      <joint name="swing" type="hinge" axis="0 1 0" range="-10 10"/>
      <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.01" mass="0.04"/>
    </body>
  </worldbody>
  <actuator>
    <position name="swing" joint="swing" kp="{kp}" ctrlrange="-10 10"
              forcerange="-{force} {force}"/>
  </actuator>
</mujoco>"""


def pendulum(kp: float, force: float) -> mujoco.MjModel:
    xml = PENDULUM.format(kp=kp, force=force)
    return mujoco.MjModel.from_xml_string(xml)


def test_a_runaway_joint_is_named_with_its_force_range_and_the_fix(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    capture_mujoco_warnings()  # as the check step does: no MUJOCO_LOG.TXT where it runs
    take_mujoco_warnings()
    # A servo far too stiff for the explicit integrator, with a placeholder force limit.
    report = check_control(pendulum(1e9, 1e9), set(), 0.05, strict=True)
    assert any("QACC" in warning for warning in take_mujoco_warnings())
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()
    runaway = [f for f in report.failures if "pseudorandom control" in f]
    assert runaway == [
        "MuJoCo warned under pseudorandom control: badqacc (x1) (at joint 'swing', its "
        "actuator's force range [-1e+09, 1e+09]); if the URDF's effort or range is a "
        "placeholder, give the real one (a rule's forcerange in actuators:), or lower "
        "actuators.frequency"
    ]
    assert report.results["menagerie_test"]["unstable_joint"] == "swing"


def test_a_servo_within_its_real_torque_passes():
    test = menagerie_test(pendulum(1.0, 2.7))
    assert test.finite and test.warnings == []
    assert test.fastest_joint == "swing" and 0 < test.fastest_speed < 100
    report = check_control(pendulum(1.0, 2.7), set(), 0.05, strict=True)
    assert not [f for f in report.failures if "pseudorandom" in f]
