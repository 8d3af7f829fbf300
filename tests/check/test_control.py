"""The control checks on hand-written models: Menagerie's pseudorandom-control test names the
joint that ran away and what to change."""

from __future__ import annotations

import mujoco
import pytest

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
    assert report.results.menagerie_test.unstable_joint == "swing"


def test_a_servo_within_its_real_torque_passes():
    test = menagerie_test(pendulum(1.0, 2.7))
    assert test.finite and test.warnings == []
    assert test.fastest_joint == "swing" and 0 < test.fastest_speed < 100
    report = check_control(pendulum(1.0, 2.7), set(), 0.05, strict=True)
    assert not [f for f in report.failures if "pseudorandom" in f]


HELD = """<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <body name="arm">
      <joint name="swing" type="hinge" axis="0 1 0" damping="0.01"/>
      <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.01" mass="0.5"/>
    </body>
  </worldbody>
  <actuator>{actuator}</actuator>
  <keyframe><key name="home" qpos="0" ctrl="0"/></keyframe>
</mujoco>"""


@pytest.mark.parametrize(
    ("actuator", "advice"),
    [
        (
            '<motor joint="swing" ctrlrange="-5 5"/>',
            "'swing' is driven by a torque motor, whose constant ctrl cannot hold a pose: "
            "hold it with a controller, or make it a position servo with a rule (actuators: "
            "{rules: [{joints: [swing], type: position}]})",
        ),
        (
            '<velocity joint="swing" kv="0.5" ctrlrange="-5 5"/>',
            "'swing' is driven by a velocity servo, which holds a speed, not a position: where "
            "it must hold a pose, make it a position servo with a rule (actuators: {rules: "
            "[{joints: [swing], type: position}]}); where a <ros2_control> velocity interface "
            "must command it (mujoco_ros2_control takes velocity on a velocity servo only, or "
            "with PID gains), it holds under a controller alone: raise check.hold_tolerance to "
            "say so",
        ),
        (
            '<position joint="swing" kp="0.5" ctrlrange="-5 5"/>',
            "stiffen its actuator (actuators.frequency, or kp in a rule)",
        ),
    ],
)
def test_hold_advice_fits_what_drives_the_joint(actuator, advice):
    """A horizontal arm that sags at home: only a position servo is told to stiffen."""
    model = mujoco.MjModel.from_xml_string(HELD.format(actuator=actuator))
    report = check_control(model, set(), 0.05, strict=True)
    held = [f for f in report.failures if f.startswith("holding home's ctrl")]
    assert len(held) == 1 and advice in held[0], report.failures
    if "position" not in actuator:
        assert "stiffen" not in held[0]


def test_a_joint_without_an_actuator_is_told_to_get_one_not_to_stiffen_it():
    """A hand-written model whose sagging joint has no actuator at all."""
    xml = HELD.format(actuator="").replace(' ctrl="0"', "")
    report = check_control(mujoco.MjModel.from_xml_string(xml), set(), 0.05, strict=False)
    [held] = [f for f in report.failures if f.startswith("holding home's ctrl")]
    assert "'swing' has no actuator, so nothing holds it: drive it with one" in held
    assert "stiffen" not in held


def test_joints_asked_to_be_passive_that_sag_fail_nothing_but_the_verdict_says_so():
    """robot.yaml's actuators: none on an arm: no failure (it was asked for), but the verdict
    does not say "check passed" over an arm that falls from home."""
    xml = HELD.format(actuator="").replace(' ctrl="0"', "")
    report = check_control(mujoco.MjModel.from_xml_string(xml), {"swing"}, 0.05, strict=True)
    results = report.results.add(loads=True)
    assert results.passes, results.failures
    assert results.hold is not None and results.hold.passive_sags
    hold = dict(results.console_lines())["hold home 1 s"]
    assert hold.startswith("every joint is passive; 1 joint without an actuator moved up to ")
    assert hold.endswith(" (swing)")
    verdict = results.console_verdict()
    assert verdict.startswith(
        "checks pass, but it does not hold home: 1 joint without an actuator (as robot.yaml's "
        "actuators ask) moves from it, 'swing' by "
    )
    # Held still (a stiff spring at home), the same passive joint is no caveat.
    stiff = xml.replace('damping="0.01"', 'damping="0.01" stiffness="1000"')
    report = check_control(mujoco.MjModel.from_xml_string(stiff), {"swing"}, 0.05, strict=True)
    assert report.results.add(loads=True).console_verdict() == "check passed"


@pytest.mark.parametrize(
    ("key", "actuator", "advice"),
    [
        (  # a hand-written keyframe without ctrl: the servo aims at 0
            '<key name="home" qpos="0.8"/>',
            '<position joint="swing" kp="50" ctrlrange="-2 2"/>',
            "the 'home' keyframe's ctrl asks the servo of 'swing' for 0, not its position "
            "there (0.8): give the keyframe a ctrl that matches its qpos",
        ),
        (  # mjcfbuild's default servo: a drive's position servo
            '<key name="home" qpos="0.8" ctrl="0.2"/>',
            '<dcmotor joint="swing" input="pos" nominal="1 20 5" controller="50 0 1 0 0 1" '
            'saturation="20 0 0" ctrlrange="-2 2"/>',
            "asks the servo of 'swing' for 0.2, not its position there (0.8)",
        ),
        (
            '<key name="home" qpos="0.8" ctrl="0.5"/>',
            '<position joint="swing" kp="50" ctrlrange="-0.5 0.5"/>',
            "'swing' is at 0.8 at home, outside its servo's ctrlrange [-0.5, 0.5]",
        ),
    ],
)
def test_a_servo_aimed_away_from_home_is_said_to_be(key, actuator, advice):
    """No stiffening helps a servo whose home ctrl is not home (a keyframe in the inputs)."""
    xml = HELD.format(actuator=actuator).replace('<key name="home" qpos="0" ctrl="0"/>', key)
    report = check_control(mujoco.MjModel.from_xml_string(xml), set(), 0.05, strict=True)
    held = [f for f in report.failures if f.startswith("holding home's ctrl")]
    assert len(held) == 1 and advice in held[0], report.failures
    assert "stiffen" not in held[0]


def test_an_effort_only_quadruped_needs_a_controller_and_the_rule_the_check_gives_stands(
    tmp_path,
):
    """ros2_control effort interfaces give torque motors holding home's gravity torques: the
    robot falls, which no stiffening fixes. The check says it needs a controller, names the
    motors and gives the rule for a passive stand; with that rule it stands."""
    import json

    import mjcfbuild
    from tests.conftest import write
    from tests.control.robots import quadruped

    legs = [
        f"{leg}_{part}_joint"
        for leg in ("FL", "FR", "RL", "RR")
        for part in ("hip", "thigh", "calf")
    ]
    joints = "".join(
        f'<joint name="{name}"><command_interface name="effort"/>'
        '<state_interface name="position"/></joint>'
        for name in legs
    )
    block = (
        '<ros2_control name="legs" type="system"><hardware><plugin>'
        f"mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>{joints}</ros2_control>"
    )
    write(
        tmp_path / "robot.urdf", quadruped(foot_offset=0.05).replace("</robot>", block + "</robot>")
    )
    bent = ", ".join(
        f"{leg}_{part}_joint: {angle}"
        for leg in ("FL", "FR", "RL", "RR")
        for part, angle in (("thigh", 0.6), ("calf", -1.2))
    )
    manifest = (
        f"name: q\nsource: {{urdf: robot.urdf}}\noptions: {{free_joint: true}}\nhome: {{{bent}}}\n"
    )
    write(tmp_path / "robot.yaml", manifest)
    result = mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    check = json.loads((result.robot.parent / ".mjcfbuild/check.json").read_text())
    assert check["passes"], check["failures"]
    why = check["needs_controller"]
    assert why.startswith("its joints are driven by torque motors (FL_hip_joint, "), why
    assert "stiffen" not in why and "(12 in all)" in why
    # Every joint is a motor: one pattern names them all
    rule = 'actuators: {rules: [{joints: ["*"], type: position}]}'
    assert rule in why
    notes = [w for w in result.warnings if "without a controller" in w]
    assert len(notes) == 1 and "stand test was not run" not in notes[0], notes

    assert "whose effort interfaces need the motors" in why
    # The passive stand the rule gives (without the block: the runtime would refuse position
    # servos on effort interfaces, and the build's check says so).
    write(tmp_path / "robot.urdf", quadruped(foot_offset=0.05))
    write(tmp_path / "robot.yaml", manifest + rule + "\n")
    result = mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    check = json.loads((result.robot.parent / ".mjcfbuild/check.json").read_text())
    assert check["passes"] and "needs_controller" not in check, check["failures"]
    assert check["stand"]["max_tilt"] < 0.2


def test_a_floating_robot_left_passive_by_robot_yaml_falls_with_that_reason_not_a_failure(
    tmp_path,
):
    """actuators: {default: none} on a quadruped: it collapses, as a fixed arm's passive joints
    sag, which the verdict says ("checks pass, but"); the check failed it advising to stiffen
    its servos, which it does not have."""
    import json

    import mjcfbuild
    from mjcfbuild.errors import BuildFailed
    from tests.conftest import write
    from tests.control.robots import quadruped

    write(tmp_path / "robot.urdf", quadruped(foot_offset=0.05))
    write(
        tmp_path / "robot.yaml",
        "name: q\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\n"
        "actuators: {default: none}\n",
    )
    result = mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    check = json.loads((result.robot.parent / ".mjcfbuild/check.json").read_text())
    assert check["passes"], check["failures"]
    why = check["needs_controller"]
    assert why.startswith("12 of its joints have no actuator, as robot.yaml's actuators ask"), why
    assert "stiffen" not in why
    # Servos too weak to carry it, beside one passive joint (a tail): the servos' failure, which
    # the passive joint moving as the robot falls does not excuse.
    tail = (
        '<link name="tail"><inertial><mass value="0.01"/><inertia ixx="1e-5" iyy="1e-5" '
        'izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial></link><joint name="tail_joint" '
        'type="revolute"><parent link="trunk"/><child link="tail"/><origin xyz="-0.3 0 0"/>'
        '<axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>'
    )
    write(
        tmp_path / "robot.urdf", quadruped(foot_offset=0.05).replace("</robot>", tail + "</robot>")
    )
    write(
        tmp_path / "robot.yaml",
        "name: q\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\nactuators:\n"
        "  rules:\n    - {joints: [tail_joint], type: none}\n"
        '    - {joints: ["*"], frequency: 0.2}\n',
    )
    with pytest.raises(BuildFailed):
        mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    check = json.loads((result.robot.parent / ".mjcfbuild/check.json").read_text())
    assert any("does not stand at home" in f for f in check["failures"]), check


def test_wheels_on_velocity_servos_are_judged_by_not_rolling_away(tmp_path):
    """A rover on a slope (gravity tilted 12 degrees): its wheels' angles are theirs to change,
    but the robot must not roll away. The check names the wheels and the kv that holds it;
    with that kv the rover stays put."""
    import json

    import mjcfbuild
    from mjcfbuild.errors import BuildFailed
    from tests.conftest import write
    from tests.control.robots import rover

    write(tmp_path / "robot.urdf", rover())
    manifest = (
        "name: r\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\n"
        "mujoco_inputs:\n  raw: '<option gravity=\"2 0 -9.81\"/>'\n"
    )
    write(tmp_path / "robot.yaml", manifest)
    with pytest.raises(BuildFailed):
        mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["stand"]["wheels"] == ["left_wheel_joint", "right_wheel_joint"]
    [failure] = check["failures"]
    assert failure.startswith("the robot rolled "), failure
    assert "wheel_joint' moved" not in failure and "stiffen" not in failure
    rule = failure[failure.index("actuators: ") : -1]
    assert rule.startswith(
        "actuators: {rules: [{joints: [left_wheel_joint, right_wheel_joint], kv: "
    )
    write(tmp_path / "robot.yaml", manifest + rule + "\n")
    mjcfbuild.build(tmp_path / "robot.yaml", jobs=1)
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"] and check["stand"]["max_roll"] < 0.05, check["failures"]
