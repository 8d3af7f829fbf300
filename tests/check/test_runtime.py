"""The model under mujoco_ros2_control's rules: each ros2_control joint's actuator is of a kind
the runtime commands through the joint's interfaces, and the check says where it is not.

The runtime's rule is restated here from its source (mujoco_system_interface.cpp,
getActuatorType and the configure_*_command_interface functions), not imported from
mjcfbuild, so the test holds the build to the runtime, not to itself.
"""

from __future__ import annotations

import json

import mujoco
import pytest

from mjcfbuild.errors import EXIT_CHECK
from tests.conftest import run_cli, write
from tests.control.helpers import build_two_link, load, readiness


def runtime_kind(model, actuator: int) -> str:
    """mujoco_ros2_control's getActuatorType: an <intvelocity> (an integrator into a fixed
    gain, an affine bias of -kp on position) is velocity; else the bias alone decides."""
    bias = model.actuator_biasprm[actuator]
    if (
        model.actuator_dyntype[actuator] == mujoco.mjtDyn.mjDYN_INTEGRATOR
        and model.actuator_gaintype[actuator] == mujoco.mjtGain.mjGAIN_FIXED
        and model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE
        and bias[0] == 0
        and bias[1] == -model.actuator_gainprm[actuator][0]
    ):
        return "velocity"
    if model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_NONE:
        return "motor"
    if model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE and bias[1] != 0:
        return "position"
    if model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE and bias[2] != 0:
        return "velocity"
    return "custom"


# The interfaces each kind takes without PID gains (torque and force are effort).
TAKES = {
    "position": {"position"},
    "velocity": {"velocity"},
    "motor": {"effort", "torque", "force"},
    "custom": {"effort", "torque", "force"},
}


def control_block(interfaces: list[str], hardware: str = "") -> str:
    commands = "".join(f'<command_interface name="{i}"/>' for i in interfaces)
    return (
        f'<ros2_control name="s" type="system"><hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin>{hardware}</hardware>'
        f'<joint name="hinge">{commands}<state_interface name="position"/></joint></ros2_control>'
    )


def check_record(folder) -> dict:
    return json.loads((folder / "mjcf/.mjcfbuild/check.json").read_text())


@pytest.mark.parametrize(
    "interfaces",
    [
        ["position"],
        ["velocity"],
        ["effort"],
        ["torque"],
        ["position", "velocity"],
        ["velocity", "effort"],
        ["position", "velocity", "effort"],
    ],
)
def test_every_command_interface_combination_gets_an_actuator_the_runtime_commands(
    tmp_path, interfaces
):
    model = load(build_two_link(tmp_path, urdf_extra=control_block(interfaces)))
    assert model.nu == 1
    kind = runtime_kind(model, 0)
    # The first interface in the runtime's own order (position, velocity, effort) is taken
    # directly: without PIDs the joint is never left without one.
    order = ["position", "velocity", "effort", "torque", "force"]
    first = min(interfaces, key=order.index)
    assert first in TAKES[kind], (interfaces, kind)
    section = check_record(tmp_path)["mujoco_ros2_control"]
    (joint,) = section["joints"]
    assert (joint["joint"], joint["kind"]) == ("hinge", kind)
    assert joint["how"][first] == "direct"
    assert check_record(tmp_path)["passes"]


def test_a_position_joint_keeps_a_position_servo_where_the_default_is_a_dcmotor(tmp_path):
    """The URDF's effort and velocity limits make a <dcmotor> of a joint no ros2_control
    block commands; one the runtime commands by position gets a <position> servo."""
    plain = load(build_two_link(tmp_path / "plain"))
    assert runtime_kind(plain, 0) == "custom"
    commanded = load(build_two_link(tmp_path / "ros", urdf_extra=control_block(["position"])))
    assert runtime_kind(commanded, 0) == "position"
    # Same force limit; its rotor inertia from the speed line is not added.
    assert list(commanded.actuator_forcerange[0]) == [-10, 10]


def test_an_interface_the_actuator_refuses_beside_one_it_takes_is_a_warning(tmp_path):
    raw = 'mujoco_inputs:\n  raw: \'<actuator><position name="hinge" joint="hinge" kp="50"/></actuator>\'\n'
    result = build_two_link(tmp_path, raw, urdf_extra=control_block(["position", "velocity"]))
    warning = next(w for w in result.warnings if "mujoco_ros2_control" in w)
    assert "velocity command interface" in warning and "hinge" in warning
    assert check_record(tmp_path)["passes"]


def test_a_joint_whose_actuator_takes_none_of_its_interfaces_fails_the_check(tmp_path):
    write(tmp_path / "robot.urdf", _two_link_with(control_block(["velocity"])))
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\nmujoco_inputs:\n"
        '  raw: \'<actuator><position name="mine" joint="hinge" kp="50"/></actuator>\'\n',
    )
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK, result.stderr
    assert (
        "joint 'hinge' commands velocity, none of which its actuator 'mine' (position, as the "
        "runtime classifies it) takes" in result.stderr
    )
    assert not check_record(tmp_path)["passes"]
    # mjcfbuild check says the same.
    again = run_cli("check", str(tmp_path / "robot.yaml"))
    assert again.code == EXIT_CHECK and "none of which its actuator 'mine'" in again.stderr


MOTOR = "actuators:\n  rules: [{joints: [hinge], type: motor}]\n"
PIDS = """mujoco_ros2_control_node:
  ros__parameters:
    pid_gains:
      position:
        hinge: {p: %s, i: 0.0, d: 2.0}
"""


def _pids_block(path) -> str:
    return control_block(["position"], f'<param name="pids_config_file">{path}</param>')


def test_pid_gains_of_the_pids_config_file_let_a_motor_take_position(tmp_path):
    """The runtime builds a PID from pid_gains.position.<joint>.p, .i and .d, read as ROS
    doubles; the file is read, and editing it reruns the check."""
    pids = tmp_path / "pids.yaml"
    write(pids, PIDS % "100.0")
    build_two_link(tmp_path, MOTOR, urdf_extra=_pids_block(pids))
    (joint,) = check_record(tmp_path)["mujoco_ros2_control"]["joints"]
    assert (joint["kind"], joint["how"], joint["starts"]) == (
        "motor",
        {"position": "pid"},
        "position",
    )
    # `p: 100` is an integer to ROS: PidROS reads no gain, and the runtime stops at start-up.
    write(pids, PIDS % "100")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK, result.stderr
    assert "robot.urdf:" in result.stderr and "takes only through PID gains" in result.stderr
    assert "pid_gains.position.hinge: its p gain 100 is not a double (write 100.0)" in result.stderr


def test_a_position_command_on_a_motor_without_pid_gains_stops_the_runtime(tmp_path):
    """Beside an effort interface the motor takes, a position interface without gains used to
    be a warning: the runtime's register_urdf_joints throws for it."""
    block = control_block(["position", "effort"])
    write(tmp_path / "robot.urdf", _two_link_with(block))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + MOTOR)
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK, result.stderr
    assert (
        "joint 'hinge' commands position on its motor actuator 'hinge', which the runtime takes "
        "only through PID gains, and no pids_config_file gives them" in result.stderr
    )


def test_a_pids_config_file_not_found_here_is_said_to_be_unchecked(tmp_path):
    result = build_two_link(tmp_path, MOTOR, urdf_extra=_pids_block("/nowhere/pids.yaml"))
    (joint,) = check_record(tmp_path)["mujoco_ros2_control"]["joints"]
    assert joint["how"] == {"position": "pid?"}
    assert any(
        "the pids_config_file /nowhere/pids.yaml could not be read here" in w
        and "hinge position" in w
        for w in result.warnings
    ), result.warnings


def test_a_joint_the_urdf_lacks_is_refused_at_its_line(tmp_path):
    """ros2_control (Jazzy and later) refuses a <ros2_control> joint the URDF does not have."""
    block = control_block(["position"]).replace('name="hinge"', 'name="hnge"')
    stderr = _fails_to_start(tmp_path, block)
    assert "robot.urdf:" in stderr
    assert "joint 'hnge' is not a joint of the URDF" in stderr
    assert "what is no joint; did you mean 'hinge'?" in stderr


FOLLOWER = (
    '<link name="tip"><inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" '
    'izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>'
    '<joint name="follower" type="revolute"><parent link="arm"/><child link="tip"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
    '<mimic joint="hinge" multiplier="1"/></joint>'
)


def test_a_urdf_mimic_joint_with_command_interfaces_is_refused_by_ros2_control(tmp_path):
    """ros2_control's parser (Jazzy and later) refuses an activated mimic joint with command
    interfaces, and one whose leader its block does not list; mimic="false" lets the joint be
    commanded on its own."""
    block = control_block(["position"]).replace(
        "</ros2_control>",
        '<joint name="follower"><command_interface name="position"/>'
        '<state_interface name="position"/></joint></ros2_control>',
    )
    _fails_to_start(tmp_path / "commanded", FOLLOWER + block)
    failures = check_record(tmp_path / "commanded")["failures"]
    assert any(
        "joint 'follower' mimics 'hinge' and has command interfaces" in f
        and "Activated mimic joints cannot have command interfaces" in f
        for f in failures
    ), failures
    alone = (
        '<ros2_control name="s" type="system"><hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware><joint name="follower">'
        '<state_interface name="position"/></joint></ros2_control>'
    )
    _fails_to_start(tmp_path / "alone", FOLLOWER + alone)
    failures = check_record(tmp_path / "alone")["failures"]
    assert any("mimics 'hinge', which its block does not list" in f for f in failures), failures
    stated = block.replace('<joint name="follower">', '<joint name="follower" mimic="false">')
    _fails_to_start(tmp_path / "stated", FOLLOWER + stated)
    failures = check_record(tmp_path / "stated")["failures"]
    assert not any("Activated mimic" in f for f in failures), failures
    assert any("'follower'" in f for f in failures)  # commanded, it needs an actuator


def test_a_param_mimic_joint_with_a_command_interface_is_a_warning_not_a_failure(tmp_path):
    """A <param name="mimic"> makes mujoco_ros2_control itself ignore the joint's command
    interfaces (it logs an error), without ros2_control's parser refusing anything."""
    block = control_block(["position"]).replace(
        "</ros2_control>",
        '<joint name="follower"><param name="mimic">hinge</param>'
        '<command_interface name="position"/><state_interface name="position"/></joint>'
        "</ros2_control>",
    )
    plain = FOLLOWER.replace('<mimic joint="hinge" multiplier="1"/>', "")
    result = build_two_link(tmp_path, urdf_extra=plain + block)
    assert any(
        "1 mimic joint (follower (mimics hinge)) declares command interfaces" in w
        for w in result.warnings
    ), result.warnings


def test_a_fixed_joint_in_a_block_is_refused_by_ros2_control(tmp_path):
    fixed = (
        '<link name="tool"/><joint name="mount" type="fixed"><parent link="arm"/>'
        '<child link="tool"/></joint>'
    )
    block = control_block(["position"]).replace(
        "</ros2_control>",
        '<joint name="mount"><state_interface name="position"/></joint></ros2_control>',
    )
    _fails_to_start(tmp_path, fixed + block)
    failures = check_record(tmp_path)["failures"]
    assert any(
        "<ros2_control> joint 'mount' is a fixed joint" in f
        and "Fixed joints do not make sense in ros2_control" in f
        for f in failures
    ), failures


def test_a_block_for_other_hardware_beside_the_runtimes_is_not_judged_as_the_runtimes(tmp_path):
    """A gripper driver's block beside mujoco_ros2_control's: its initial_keyframe is not the
    runtime's (the build failed on it), and its joints are said to be unserved."""
    runtime = control_block(["position"]).replace(
        "<hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>",
        "<hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin>"
        '<param name="initial_keyframe">home</param></hardware>',
    )
    driver = (
        '<ros2_control name="gripper" type="system"><hardware>'
        "<plugin>robotiq_driver/RobotiqGripperHardwareInterface</plugin>"
        '<param name="initial_keyframe">pregrasp</param></hardware>'
        '<joint name="hinge"><command_interface name="position"/></joint></ros2_control>'
    )
    result = build_two_link(tmp_path, urdf_extra=runtime + driver)
    assert check_record(tmp_path)["passes"], check_record(tmp_path)["failures"]
    assert any(
        "the <ros2_control> block for robotiq_driver/RobotiqGripperHardwareInterface is not "
        "the runtime's" in w
        for w in result.warnings
    ), result.warnings


def test_an_intvelocity_takes_a_velocity_command_directly(tmp_path):
    """The runtime classifies an <intvelocity> as a velocity actuator (its ctrl is a speed);
    the check took it for a position servo and said the runtime would not start."""
    raw = (
        'home: {hinge: 0.5}\nmujoco_inputs:\n  raw: \'<actuator><intvelocity name="hinge" '
        'joint="hinge" kp="50" actrange="-1 1"/></actuator>\'\n'
    )
    result = build_two_link(tmp_path, raw, urdf_extra=control_block(["velocity"]))
    (joint,) = check_record(tmp_path)["mujoco_ros2_control"]["joints"]
    assert (joint["kind"], joint["how"]) == ("velocity", {"velocity": "direct"})
    # Its home: at rest (ctrl, a speed, 0) aiming at the pose (act), which it holds; the
    # keyframe wrote the position into ctrl, and the hold check failed.
    model = load(result)
    assert (list(model.key_ctrl[0]), list(model.key_act[0])) == ([0.0], [0.5])
    assert check_record(tmp_path)["passes"]


def test_effort_joints_are_said_to_start_without_the_keyframes_torques(tmp_path):
    result = build_two_link(tmp_path, urdf_extra=control_block(["effort"]))
    assert any("1 joint (hinge) starts under effort control" in w for w in result.warnings)


def test_a_floating_robot_is_told_which_free_joint_odometry_needs(tmp_path):
    result = build_two_link(
        tmp_path, "options: {free_joint: true}\n", urdf_extra=control_block(["position"])
    )
    assert any(
        "no odom_free_joint_name is given (it defaults to 'floating_base_joint')" in w
        and '<param name="odom_free_joint_name">base_freejoint</param>' in w
        for w in result.warnings
    ), result.warnings
    named = control_block(["position"], '<param name="odom_free_joint_name">base</param>')
    result = build_two_link(tmp_path / "named", "options: {free_joint: true}\n", named)
    assert any(
        w.startswith("robot.urdf:15: mujoco_ros2_control: odom_free_joint_name names 'base'")
        for w in result.warnings
    ), result.warnings


def _two_link_with(extra: str) -> str:
    from tests.conftest import two_link_urdf

    return two_link_urdf(extra=extra)


def test_the_reference_demo_passes_the_runtimes_rules(demo):
    result = run_cli("build", str(demo / "robot.yaml"))
    assert result.code == 0, result.stderr
    record = check_record(demo)
    assert record["passes"], record["failures"]
    section = record["mujoco_ros2_control"]
    assert {j["joint"]: j["kind"] for j in section["joints"]} == {
        "joint1": "position",
        "joint2": "position",
        "gripper_left_finger_joint": "position",  # its tendon's actuator, named like it
    }
    assert all(m["found"] for s in section["sensors"] for m in s["mjcf"])
    assert [(d["sensor"], d["found"]) for d in section["devices"]] == [
        ("camera", True),
        ("lidar", True),
    ]
    assert section["devices"][1]["rays"] == 24
    # The report names the user's tendon actuator and its kind (it showed "" and "user").
    records = {r["joint"]: r for r in readiness(demo)["actuators"]}
    gripper = records["gripper_left_finger_joint"]
    assert (gripper["name"], gripper["type"]) == ("gripper_left_finger_joint", "position")
    # Its use_pid variant declares velocity beside position on position actuators, which the
    # runtime logs as an error for velocity: a warning, not a failure.
    assert "velocity command interface" in result.stderr


def test_the_example_arm_with_its_ros2_control_block_passes(arm):
    manifest = arm / "robot.yaml"
    manifest.write_text(
        manifest.read_text().replace(
            "with_camera: true", "with_camera: true\n    ros2_control: true"
        )
    )
    result = run_cli("build", str(manifest))
    assert result.code == 0, result.stderr
    record = json.loads((arm / "mjcf/.mjcfbuild/check.json").read_text())
    assert record["passes"], record["failures"]
    kinds = {j["joint"]: j["kind"] for j in record["mujoco_ros2_control"]["joints"]}
    assert kinds == {
        "shoulder_pan": "position",
        "shoulder_lift": "position",
        "elbow": "position",
        "wrist_roll": "velocity",
        "left_finger_joint": "position",
    }
    written = {m["name"] for s in record["mujoco_ros2_control"]["sensors"] for m in s["mjcf"]}
    assert written == {
        "wrist_ft_force",
        "wrist_ft_torque",
        "base_imu_quat",
        "base_imu_gyro",
        "base_imu_accel",
    }
    assert "mujoco_ros2_control" not in result.stderr  # nothing refused


def test_an_effort_command_on_a_dcmotor_is_warned_about(tmp_path):
    """The runtime takes a <dcmotor> for a custom actuator and writes efforts into its ctrl,
    which a position-input <dcmotor> reads as a target angle."""
    raw = (
        'mujoco_inputs:\n  raw: \'<actuator><dcmotor name="hinge" joint="hinge" input="pos" '
        'nominal="1 10 5" controller="50 0 2 0 0 1" saturation="10 0 0"/></actuator>\'\n'
    )
    result = build_two_link(tmp_path, raw, urdf_extra=control_block(["effort"]))
    (joint,) = check_record(tmp_path)["mujoco_ros2_control"]["joints"]
    assert (joint["kind"], joint["how"], joint["dcmotor"]) == ("custom", {"effort": "direct"}, True)
    assert any("command effort on a <dcmotor>" in w for w in result.warnings), result.warnings


def _fails_to_start(tmp_path, urdf_extra: str, manifest_extra: str = "") -> str:
    """Build the two-link robot; assert the check fails; its stderr."""
    write(tmp_path / "robot.urdf", _two_link_with(urdf_extra))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + manifest_extra)
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK, result.stdout + result.stderr
    return result.stderr


def test_an_initial_keyframe_the_model_lacks_stops_the_runtime(tmp_path):
    """mujoco_ros2_control's register_mujoco_actuators: "Failed to apply initial keyframe:
    'start_90'", and it does not start; the check passed a model with only 'home'."""
    hardware = '<param name="initial_keyframe">start_90</param>'
    stderr = _fails_to_start(tmp_path, control_block(["position"], hardware))
    # At the param's line.
    assert (
        "robot.urdf:15: check: <hardware> param initial_keyframe names keyframe 'start_90', "
        "which the model does not have (its keyframes: 'home')"
    ) in stderr
    # What mujoco_system_interface.cpp logs, word for word (it said "Failed to find keyframe").
    assert (
        "mujoco_ros2_control stops at start-up (\"Failed to apply initial keyframe: 'start_90'\", "
        'then "Failed to register MuJoCo actuators, exiting..."); name one of them'
    ) in stderr
    fixed = '<param name="initial_keyframe">home</param>'
    build_two_link(tmp_path / "fixed", urdf_extra=control_block(["position"], fixed))
    assert check_record(tmp_path / "fixed")["passes"]


def test_a_transmission_naming_no_joint_or_actuator_stops_the_runtime(tmp_path):
    """register_transmissions looks each transmission actuator up as a joint, then as an
    actuator: "Transmission actuator 'actuator1' not found" stops it."""

    def block(actuator: str) -> str:
        return control_block(["position"]).replace(
            "</ros2_control>",
            '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
            f'<actuator name="{actuator}" role="actuator1"/><joint name="hinge" role="joint1">'
            "<mechanical_reduction>1.0</mechanical_reduction></joint></transmission>"
            "</ros2_control>",
        )

    stderr = _fails_to_start(tmp_path, block("actuator1"))
    assert "of joint 'hinge' names actuator 'actuator1', which is neither a joint" in stderr
    build_two_link(tmp_path / "fixed", urdf_extra=block("hinge"))
    assert check_record(tmp_path / "fixed")["passes"]
    # A block written for a real robot's driver (TIAGo Pro's robot_control/RobotControl) is
    # not run by mujoco_ros2_control as written: said, not failed.
    driver = block("actuator1").replace(
        "<hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>",
        "<hardware><plugin>robot_control/RobotControl</plugin></hardware>",
    )
    result = build_two_link(tmp_path / "driver", urdf_extra=driver)
    assert check_record(tmp_path / "driver")["passes"]
    assert any(
        "<ros2_control> transmissions for the hardware plugin robot_control/RobotControl are "
        "not run by mujoco_ros2_control as written"
        in warning
        and "transmission #1 of joint 'hinge' names actuator 'actuator1'" in warning
        for warning in result.warnings
    ), result.warnings


def _transmission(body: str) -> str:
    return control_block(["position"]).replace(
        "</ros2_control>",
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        f"{body}</transmission></ros2_control>",
    )


def test_a_transmission_the_runtimes_register_transmissions_refuses_stops_it(tmp_path):
    """From register_transmissions (2026): a transmission without an <actuator> stops it ("has
    no joints or actuators defined"), and so does one naming an MJCF actuator by its own name:
    the handles are found by the joint an actuator drives ("Actuator ... not found in the
    MuJoCo actuator data"), though the first lookup accepts an actuator's name."""
    joint = '<joint name="hinge" role="joint1"/>'
    stderr = _fails_to_start(tmp_path / "none", _transmission(joint))
    assert "transmission #1 of joint 'hinge' has no <actuator>" in stderr
    motor = (
        'mujoco_inputs:\n  raw: \'<actuator><motor name="hinge_motor" joint="hinge"/>'
        "</actuator>'\n"
    )
    named = _transmission('<actuator name="hinge_motor" role="actuator1"/>' + joint)
    _fails_to_start(tmp_path / "named", named, motor)
    (failure,) = [f for f in check_record(tmp_path / "named")["failures"] if "transmission" in f]
    assert "names actuator 'hinge_motor' by the MJCF actuator's name" in failure
    assert failure.endswith("name joint 'hinge'")


def test_a_reduction_between_a_joint_and_its_own_actuator_misreports_its_state(tmp_path):
    """joint_command_to_actuator_command copies the joint's command onto the actuator of its
    name after the transmission wrote it, so a position command of 0.2 drives the joint to 0.2;
    actuator_state_to_joint_state has no such step, so the state read back is halved. The
    runtime starts: a warning (the check failed, saying the joint went to 0.4)."""
    geared = _transmission(
        '<actuator name="hinge" role="actuator1"/><joint name="hinge" role="joint1">'
        "<mechanical_reduction>2.0</mechanical_reduction></joint>"
    )
    result = build_two_link(tmp_path / "geared", urdf_extra=geared)
    assert check_record(tmp_path / "geared")["passes"]
    assert (
        "robot.urdf:15: transmission #1 of joint 'hinge' has a reduction of 2 to its own "
        "actuator: mujoco_ros2_control passes the joint's commands to the actuator as they are "
        "(the joint's own command overwrites the transmission's) but reports its state through "
        "the transmission, so a joint at 0.4 reads 0.2; in the block the runtime runs, set the "
        "reduction to 1 (or leave the transmission out)"
    ) in result.warnings, result.warnings
    # SimpleTransmission reads the joint's reduction only: one on the <actuator> is no gear.
    actuator_side = _transmission(
        '<actuator name="hinge" role="actuator1"><mechanical_reduction>2.0'
        '</mechanical_reduction></actuator><joint name="hinge" role="joint1"/>'
    )
    plain = build_two_link(tmp_path / "actuator_side", urdf_extra=actuator_side)
    assert not [w for w in plain.warnings if "own actuator" in w], plain.warnings
    # A reduction of 0 leaves the runtime a transmission its loader could not make.
    zero = geared.replace(">2.0<", ">0<")
    _fails_to_start(tmp_path / "zero", zero)
    failures = check_record(tmp_path / "zero")["failures"]
    assert any(
        "has a mechanical_reduction of 0, which SimpleTransmission refuses" in f for f in failures
    ), failures


def test_a_tendon_actuator_named_like_no_joint_stops_the_runtime(tmp_path):
    """register_mujoco_actuators takes every actuator of the model, a tendon's by the joint of
    its name: "Tendon actuator 'grip' has no matching joint" stops it (the MJCF hand's
    'hand_grip' on the example arm with its ros2_control block)."""
    raw = (
        'mujoco_inputs:\n  raw: \'<tendon><fixed name="split"><joint joint="hinge" '
        'coef="1"/></fixed></tendon><actuator><position name="grip" tendon="split" kp="5"/>'
        "</actuator>'\n"
    )
    _fails_to_start(tmp_path, control_block(["position"]), raw)
    failures = check_record(tmp_path)["failures"]
    assert any(
        "actuator 'grip' drives tendon 'split' and no joint is named like it" in failure
        for failure in failures
    ), failures


def test_a_pids_config_file_that_appears_later_reruns_the_check(tmp_path):
    """Missing at the first build (a warning that it was not read), then written with an
    integer gain: the next build was a no-op that replayed the warning."""
    pids = tmp_path / "later" / "pids.yaml"
    build_two_link(tmp_path, MOTOR, urdf_extra=_pids_block(pids))
    write(pids, PIDS % "100")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK, result.stdout + result.stderr
    assert "its p gain 100 is not a double" in result.stderr


def test_a_pids_config_file_ros_cannot_load_fails_and_an_empty_one_defines_no_gains(tmp_path):
    pids = tmp_path / "pids dir" / "pids.yaml"
    write(pids, "mujoco_ros2_control_node:\n  ros__parameters: [1, 2\n")
    write(tmp_path / "robot.urdf", _two_link_with(_pids_block(pids)))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + MOTOR)
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK
    record = check_record(tmp_path)
    assert any("is no ROS parameter file (line 2" in f for f in record["failures"]), record
    write(pids, "")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK and "the pids_config_file gives none" in result.stderr
    # The joint does not start, so it is not also said to start under effort control.
    assert "starts under effort control" not in result.stderr


def test_a_start_away_from_home_without_an_initial_keyframe_is_said(tmp_path):
    # The runtime applies no keyframe unless <hardware> names one: a joint with a position
    # state interface starts at its initial_value, 0 without one, whatever home says.
    moved = build_two_link(tmp_path / "moved", "home: {hinge: 0.5}\n", control_block(["position"]))
    said = [w for w in moved.warnings if "names no initial_keyframe" in w]
    assert len(said) == 1, moved.warnings
    assert "1 joint away from the home keyframe" in said[0]
    assert "hinge at 0 instead of 0.5" in said[0]
    assert '<param name="initial_keyframe">home</param>' in said[0]
    keyframe = '<param name="initial_keyframe">home</param>'
    named = build_two_link(
        tmp_path / "named", "home: {hinge: 0.5}\n", control_block(["position"], keyframe)
    )
    assert not [w for w in named.warnings if "initial_keyframe" in w], named.warnings
    # home taken from initial_value: the runtime starts there too.
    block = control_block(["position"]).replace(
        '<state_interface name="position"/>',
        '<state_interface name="position"><param name="initial_value">0.4</param>'
        "</state_interface>",
    )
    same = build_two_link(tmp_path / "same", urdf_extra=block)
    assert not [w for w in same.warnings if "initial_keyframe" in w], same.warnings


def test_a_transmission_to_a_joint_without_an_actuator_stops_the_runtime(tmp_path):
    """register_transmissions: "Actuator ... is passive and cannot be used in a transmission"."""
    passive = control_block([]).replace(
        "</ros2_control>",
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        '<actuator name="hinge" role="actuator1"/><joint name="hinge" role="joint1"/>'
        "</transmission></ros2_control>",
    )
    _fails_to_start(tmp_path, passive, "actuators: {default: none}\n")
    failures = check_record(tmp_path)["failures"]
    # get_actuator_id finds no actuator on the joint nor of its name, and register_transmissions
    # stops there, before its actuator data could call the joint passive.
    assert any(
        "names actuator 'hinge', a joint without an actuator: mujoco_ros2_control stops at "
        'start-up ("Transmission actuator ... not found in MuJoCo model")' in f
        for f in failures
    ), failures


def test_a_camera_without_resolution_and_a_lidar_short_of_its_max_angle_are_said(tmp_path):
    """The runtime renders a camera without a resolution at 1 x 1, and scans int((max - min)
    / increment) + 1 rays: -0.3 to 0.3 by 0.025 leaves out the ray at 0.3."""
    sensors = (
        '<sensor name="cam"><param name="image_topic">/image</param></sensor><sensor name="laser">'
        '<param name="frame_name">arm</param><param name="min_angle">-0.3</param>'
        '<param name="max_angle">0.3</param><param name="angle_increment">0.025</param>'
        '<param name="laserscan_topic">/scan</param></sensor>'
    )
    inputs = (
        "mujoco_inputs:\n  cameras: [{name: cam, link: arm}]\n"
        "  lidars: [{sensor_name: rf, link: arm, min_angle: -0.3, max_angle: 0.3, "
        "angle_increment: 0.025}]\n"
        '  raw: \'<sensor><rangefinder name="laser" site="rf"/></sensor>\'\n'
    )
    block = control_block(["position"], '<param name="initial_keyframe">home</param>')
    result = build_two_link(
        tmp_path, inputs, block.replace("</ros2_control>", sensors + "</ros2_control>")
    )
    said = "\n".join(result.warnings)
    assert "camera 'cam' has no resolution, so mujoco_ros2_control renders it at" in said
    assert "lidar sensor 'laser'" in said and "scans 24 rays and none at max_angle" in said


FIXED = (
    '<link name="tool"/><joint name="mount" type="fixed"><parent link="arm"/>'
    '<child link="tool"/></joint>'
)
WRIST = (
    '<link name="hand"><inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" '
    'izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>'
    '<joint name="wrist" type="revolute"><parent link="arm"/><child link="hand"/>'
    '<origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>'
    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
)


def test_a_transmission_of_a_fixed_or_unlisted_joint_is_refused_by_ros2_control(tmp_path):
    """ros2_control's parser fills a transmission joint's interfaces from its block's <joint>
    (auto_fill_transmission_interfaces): a joint the block does not list is refused ("... is
    not available in component"), and so is a fixed one, which no block may list. A reduction
    on a fixed joint through the arm's actuator got no finding."""
    fixed = _transmission(
        '<actuator name="hinge" role="actuator1"/><joint name="mount" role="joint1">'
        "<mechanical_reduction>2</mechanical_reduction></joint>"
    )
    _fails_to_start(tmp_path / "fixed", FIXED + fixed)
    failures = check_record(tmp_path / "fixed")["failures"]
    (failure,) = [f for f in failures if "transmission" in f]
    assert failure.startswith("robot.urdf:")
    assert "transmission #1 of joint 'mount' names a fixed joint" in failure
    assert "ros2_control refuses the description at start-up" in failure
    # A moving joint, with an actuator of its own, that the block does not list.
    unlisted = _transmission(
        '<actuator name="wrist" role="actuator1"/><joint name="wrist" role="joint1"/>'
    )
    _fails_to_start(tmp_path / "unlisted", WRIST + unlisted)
    failures = check_record(tmp_path / "unlisted")["failures"]
    assert [f for f in failures if "transmission" in f] == [
        "robot.urdf:15: transmission #1 of joint 'wrist' names a joint its <ros2_control> "
        'block does not list: ros2_control refuses the description at start-up ("Transmission '
        '... declared joint ... is not available in component ..."); list the joint in the '
        "block, or leave it out of the transmission"
    ], failures


def test_a_transmission_element_without_a_role_is_refused_in_every_block(tmp_path):
    """parse_transmission_from_xml reads role="..." of each <joint> and <actuator> and throws
    without it ("no attribute role in actuator tag"), in a real robot's driver block too."""
    roleless = _transmission('<actuator name="hinge"/><joint name="hinge" role="joint1"/>')
    driver = roleless.replace(
        "<hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>",
        "<hardware><plugin>robot_control/RobotControl</plugin></hardware>",
    )
    _fails_to_start(tmp_path, driver)
    failures = check_record(tmp_path)["failures"]
    assert any(
        "transmission #1: its actuator 'hinge' has no role attribute: ros2_control refuses the "
        'description at start-up ("no attribute role in ... tag")' in f
        for f in failures
    ), failures


def _follower_block(actuator: str, reduction: str) -> str:
    """The arm's block with the mimic follower listed (no command interfaces: its leader
    is listed) and a transmission of the follower from ``actuator``."""
    return FOLLOWER + control_block(["position"]).replace(
        "</ros2_control>",
        '<joint name="follower"><state_interface name="position"/></joint>'
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        f'<actuator name="{actuator}" role="actuator1"/><joint name="follower" role="joint1">'
        f"<mechanical_reduction>{reduction}</mechanical_reduction></joint></transmission>"
        "</ros2_control>",
    )


def test_a_mimic_followers_transmission_stops_the_runtime_or_misreports_it(tmp_path):
    """A mimic follower has no actuator (MuJoCo moves it by the equality its <mimic> became):
    naming it as the transmission's actuator stops register_transmissions. Through the
    leader's actuator the runtime starts, and reports the follower's position as the leader's
    over the reduction; the equality moves it at 1 x the leader. Neither got a finding."""
    _fails_to_start(tmp_path / "own", _follower_block("follower", "2"))
    failures = check_record(tmp_path / "own")["failures"]
    assert [f for f in failures if "transmission" in f] == [
        "robot.urdf:15: transmission #1 of joint 'follower' names actuator 'follower', a mimic "
        "follower of 'hinge' that MuJoCo moves by an equality, not by an actuator: "
        'mujoco_ros2_control stops at start-up ("Transmission actuator ... not found in MuJoCo '
        "model\"); leave the transmission out: the follower follows 'hinge'"
    ], failures
    result = build_two_link(tmp_path / "leader", urdf_extra=_follower_block("hinge", "2"))
    assert check_record(tmp_path / "leader")["passes"]
    assert (
        "robot.urdf:15: transmission #1 of joint 'follower' reads the mimic follower's state "
        "from actuator 'hinge': mujoco_ros2_control reports the follower at hinge / 2, where "
        "MuJoCo moves it at 1 x hinge by its <mimic>; in the block the runtime runs, leave the "
        "follower out of the transmission (the runtime then reports the follower's own joint)"
    ) in result.warnings, result.warnings
    # A reduction of 1 reports the follower where the equality puts it: nothing to say.
    same = build_two_link(tmp_path / "same", urdf_extra=_follower_block("hinge", "1"))
    assert not [w for w in same.warnings if "transmission" in w], same.warnings


def test_actuators_and_joints_the_runtime_cannot_register_stop_it(tmp_path):
    """register_mujoco_actuators takes joint, tendon and site actuators only ("Unsupported
    transmission type": an <adhesion> acts on a body), and on_init stops where a non-free
    joint has no name; neither got a finding."""
    adhesion = (
        'mujoco_inputs:\n  raw: \'<actuator><adhesion name="grip" body="arm" '
        'ctrlrange="0 1" gain="1"/></actuator>\'\n'
    )
    _fails_to_start(tmp_path / "adhesion", control_block(["position"]), adhesion)
    assert (
        "actuator 'grip' has a body transmission, which mujoco_ros2_control does not take: it "
        'stops at start-up ("Unsupported transmission type"); drive a joint, a tendon or a '
        "site instead"
    ) in check_record(tmp_path / "adhesion")["failures"]
    # An MJCF with an unnamed hinge, checked against a URDF with a <ros2_control> block.
    write(tmp_path / "p.urdf", _two_link_with(control_block(["position"])))
    write(
        tmp_path / "p.xml",
        '<mujoco><worldbody><body name="arm"><joint axis="0 1 0"/><geom size="0.05"/></body>'
        "</worldbody></mujoco>",
    )
    result = run_cli("check", "--urdf", "p.urdf", "--mjcf", "p.xml", cwd=tmp_path)
    assert (
        "1 joint of the model (in body arm) has no name: mujoco_ros2_control stops at start-up "
        '("All non-free joints must have names"); name them'
    ) in result.stderr, result.stderr


def test_a_transmissions_joints_with_different_command_interfaces_stop_the_runtime(tmp_path):
    """register_transmissions: "All joints of transmission ... must have the same command
    interfaces", checked before the transmission is loaded."""
    block = control_block(["position"]).replace(
        "</ros2_control>",
        '<joint name="wrist"><command_interface name="velocity"/>'
        '<state_interface name="position"/></joint>'
        '<transmission name="d"><plugin>transmission_interface/DifferentialTransmission</plugin>'
        '<actuator name="hinge" role="actuator1"/><actuator name="wrist" role="actuator2"/>'
        '<joint name="hinge" role="joint1"/><joint name="wrist" role="joint2"/></transmission>'
        "</ros2_control>",
    )
    _fails_to_start(tmp_path / "different", WRIST + block)
    assert [f for f in check_record(tmp_path / "different")["failures"] if "transmission" in f] == [
        "robot.urdf:15: transmission #1 of joint 'hinge' and joint 'wrist' have different "
        "command interfaces in their block (position; velocity): mujoco_ros2_control stops at "
        'start-up ("All joints of transmission ... must have the same command interfaces"); '
        "give them the same ones"
    ]
    same = block.replace(
        '<command_interface name="velocity"/>', '<command_interface name="position"/>'
    )
    build_two_link(tmp_path / "same", urdf_extra=WRIST + same)
    assert check_record(tmp_path / "same")["passes"], check_record(tmp_path / "same")["failures"]
    # An actuator the model lacks is said once for the transmission, not once per joint.
    unknown = same.replace(
        '<actuator name="wrist" role="actuator2"/>', '<actuator name="m2" role="actuator2"/>'
    )
    _fails_to_start(tmp_path / "unknown", WRIST + unknown)
    failures = check_record(tmp_path / "unknown")["failures"]
    assert len([f for f in failures if "names actuator 'm2'" in f]) == 1, failures


def test_a_joint_driven_only_through_a_transmission_takes_its_actuators_interfaces(tmp_path):
    """register_urdf_joints gives a joint without an actuator of its own the actuators of its
    block's transmission (get_joint_actuator_names): 'hinge' commands position through the
    servo on 'wrist'. The check said it had no actuator."""
    block = control_block(["position"]).replace(
        "</ros2_control>",
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        '<actuator name="wrist" role="actuator1"/><joint name="hinge" role="joint1"/>'
        "</transmission></ros2_control>",
    )
    servo = (
        "actuators: {rules: [{joints: [hinge, wrist], type: none}]}\n"
        "mujoco_inputs:\n  raw: '<actuator><position "
        'name="wrist_servo" joint="wrist" kp="5"/></actuator>\'\n'
    )
    build_two_link(tmp_path, servo, WRIST + block)
    record = check_record(tmp_path)
    assert record["passes"], record["failures"]
    (joint,) = record["mujoco_ros2_control"]["joints"]
    assert (joint["joint"], joint["actuator"], joint["kind"]) == (
        "hinge",
        "wrist_servo",
        "position",
    )


def _driver(block: str) -> str:
    """``block`` written for a real robot's driver (TIAGo Pro's), not for the runtime."""
    return block.replace(
        "<hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>",
        "<hardware><plugin>robot_control/RobotControl</plugin></hardware>",
    )


def test_a_block_child_the_parser_does_not_know_is_refused_in_every_block(tmp_path):
    """parse_resource_from_xml reads <hardware>, <joint>, <sensor>, <gpio> and <transmission>
    and throws on any other element ("invalid tag name actuator"), whatever the block's plugin;
    a comment is no element. The check passed such a block."""
    stray = control_block(["position"]).replace(
        "</ros2_control>", '<!-- a note --><actuator name="m1"/></ros2_control>'
    )
    _fails_to_start(tmp_path / "stray", stray)
    assert check_record(tmp_path / "stray")["failures"] == [
        "robot.urdf:15: <ros2_control> holds a <actuator> element, which ros2_control's parser "
        'does not know: it refuses the description at start-up ("invalid tag name actuator"); '
        "keep only <hardware>, <joint>, <sensor>, <gpio>, <transmission> in the block, and move "
        "the rest out of it"
    ]
    # The parser reads every block, a driver's too; a near miss gets the tag it meant.
    _fails_to_start(tmp_path / "driver", _driver(stray.replace("<actuator", "<sensors")))
    (failure,) = check_record(tmp_path / "driver")["failures"]
    assert "holds a <sensors> element" in failure
    assert failure.endswith("; did you mean 'sensor'?"), failure


def test_a_block_transmission_without_a_joint_stops_the_runtime(tmp_path):
    """register_transmissions: "Transmission 't' has no joints or actuators defined"; the
    check made one record per <joint> and so judged nothing of a transmission without one."""
    jointless = _transmission('<actuator name="hinge" role="actuator1"/>')
    _fails_to_start(tmp_path / "jointless", jointless)
    assert check_record(tmp_path / "jointless")["failures"] == [
        "robot.urdf:15: transmission #1 has no <joint>: mujoco_ros2_control stops at start-up "
        '("Transmission ... has no joints or actuators defined"); name the joint it drives in a '
        '<joint name="..." role="joint1">, or leave the transmission out'
    ]
    # In a driver's block: what the runtime would do once swapped in, as a warning.
    result = build_two_link(tmp_path / "driver", urdf_extra=_driver(jointless))
    assert check_record(tmp_path / "driver")["passes"]
    assert any(
        "transmissions for the hardware plugin robot_control/RobotControl" in warning
        and "transmission #1 has no <joint>" in warning
        for warning in result.warnings
    ), result.warnings


def test_a_joint_without_position_velocity_or_effort_interfaces_is_said(tmp_path):
    """export_state_interfaces and export_command_interfaces export a joint's position,
    velocity and effort (torque, force) interfaces only: a joint with none of them, commanded
    by nothing, is one the runtime serves nothing of."""
    block = control_block(["position"]).replace(
        "</ros2_control>",
        '<joint name="wrist"><state_interface name="temperature"/></joint></ros2_control>',
    )
    result = build_two_link(tmp_path / "bare", urdf_extra=WRIST + block)
    assert check_record(tmp_path / "bare")["passes"]
    assert (
        "robot.urdf:15: mujoco_ros2_control: 1 <ros2_control> joint (wrist) has no position, "
        "velocity or effort interface, so the runtime exports none for it: "
        "joint_state_broadcaster publishes no state of it and no controller can claim it; add "
        '<state_interface name="position"/> (or leave the joint out of the block)'
    ) in result.warnings, result.warnings
    served = block.replace('"temperature"', '"position"')
    plain = build_two_link(tmp_path / "served", urdf_extra=WRIST + served)
    assert not [w for w in plain.warnings if "exports none" in w], plain.warnings


def test_a_transmission_type_no_loader_has_stops_the_runtime(tmp_path):
    """register_transmissions asks the transmission loader for the <plugin> class ("Transmission
    't' of type '...' not available"): transmission_interface exports three, by pluginlib's
    lookup name, not the C++ class name; another package's plugin loads only where that package
    is installed, which the check cannot see (a warning)."""
    body = '<actuator name="hinge" role="actuator1"/><joint name="hinge" role="joint1"/>'
    cpp = _transmission(body).replace(
        "transmission_interface/SimpleTransmission", "transmission_interface::SimpleTransmission"
    )
    _fails_to_start(tmp_path / "cpp", cpp)
    assert check_record(tmp_path / "cpp")["failures"] == [
        "robot.urdf:15: transmission #1 of joint 'hinge' is of type "
        "'transmission_interface::SimpleTransmission', which transmission_interface does not "
        'export: mujoco_ros2_control stops at start-up ("... of type '
        "'transmission_interface::SimpleTransmission' not available\"); use one of "
        "transmission_interface/SimpleTransmission, transmission_interface/DifferentialTransmission, "
        "transmission_interface/FourBarLinkageTransmission; did you mean "
        "'transmission_interface/SimpleTransmission'?"
    ]
    # No <plugin> at all: ros2_control's parse_transmission_from_xml calls GetText() on the
    # element it did not find, and the parse crashes; the check said the runtime logs "... of
    # type '' not available", which only an empty <plugin> leads to.
    typeless = _transmission(body).replace(
        "<plugin>transmission_interface/SimpleTransmission</plugin>", ""
    )
    _fails_to_start(tmp_path / "typeless", typeless)
    assert check_record(tmp_path / "typeless")["failures"] == [
        "robot.urdf:15: transmission #1 has no <plugin>: ros2_control's parser "
        "(parse_transmission_from_xml) reads the transmission's type from that element without "
        "checking it is there, calling GetText() on a null pointer, so the controller manager "
        "crashes while parsing the robot description at start-up (undefined behaviour: a "
        "segmentation fault in practice), before any hardware starts; give it "
        "<plugin>transmission_interface/SimpleTransmission</plugin>"
    ]
    empty = _transmission(body).replace(
        "<plugin>transmission_interface/SimpleTransmission</plugin>", "<plugin/>"
    )
    _fails_to_start(tmp_path / "empty", empty)
    assert check_record(tmp_path / "empty")["failures"] == [
        "robot.urdf:15: transmission #1 of joint 'hinge' has an empty <plugin> (ros2_control's "
        "parser logs \"text not specified in the plugin tag\" and reads the type as ''): "
        "mujoco_ros2_control stops at start-up (\"... of type '' not available\"); give it "
        "<plugin>transmission_interface/SimpleTransmission</plugin>"
    ]
    vendor = cpp.replace("transmission_interface::SimpleTransmission", "acme/HarmonicDrive")
    # A package whose name only begins like transmission_interface's is another package: a
    # warning, not "which transmission_interface does not export".
    lookalike = cpp.replace(
        "transmission_interface::SimpleTransmission", "transmission_interface_extras/Harmonic"
    )
    for name, urdf, kind in (
        ("vendor", vendor, "acme/HarmonicDrive"),
        ("lookalike", lookalike, "transmission_interface_extras/Harmonic"),
    ):
        result = build_two_link(tmp_path / name, urdf_extra=urdf)
        assert check_record(tmp_path / name)["passes"], check_record(tmp_path / name)
        assert any(
            w.startswith(
                f"robot.urdf:15: transmission #1 of joint 'hinge' is of type '{kind}', a plugin "
                "of another package than transmission_interface"
            )
            for w in result.warnings
        ), result.warnings


def test_a_transmission_through_a_site_actuator_misreports_its_joint(tmp_path):
    """register_mujoco_actuators registers a site actuator under its own name with the qpos of
    the joint whose index is the site's, and register_transmissions takes that entry: the
    transmission reports 'hinge' from another joint. The check passed it. An actuator of a kind
    the runtime does not register (an <adhesion>, on a body) stops it."""
    site = (
        'mujoco_inputs:\n  raw: \'<actuator><motor name="thrust" site="arm" '
        'gear="0 0 1 0 0 0"/></actuator>\'\n'
    )
    body = '<actuator name="thrust" role="actuator1"/><joint name="hinge" role="joint1"/>'
    result = build_two_link(tmp_path / "site", site, WRIST + _transmission(body))
    assert check_record(tmp_path / "site")["passes"]
    model = load(result)
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "arm")
    read = model.joint(index).name if index < model.njnt else None
    assert read == "wrist", read  # what the test's words below rely on
    assert (
        "robot.urdf:15: transmission #1 of joint 'hinge' names actuator 'thrust', which acts at "
        "site 'arm': mujoco_ros2_control registers a site actuator with the state of the joint "
        "whose index is the site's, so it reports joint 'hinge' from joint 'wrist' (site #1 "
        "read as joint #1); name a joint actuator (the joint it drives) in the transmission"
    ) in result.warnings, result.warnings
    adhesion = site.replace(
        'motor name="thrust" site="arm" gear="0 0 1 0 0 0"',
        'adhesion name="thrust" body="arm" ctrlrange="0 1" gain="1"',
    )
    assert adhesion != site
    _fails_to_start(tmp_path / "body", _transmission(body), adhesion)
    assert any(
        f.startswith("actuator 'thrust' has a body transmission")
        for f in check_record(tmp_path / "body")["failures"]
    )


def test_a_reduction_to_its_own_actuator_started_from_a_keyframe_moves_the_joint(tmp_path):
    """Started from initial_keyframe, initialize_initial_positions copies the joint's state,
    read through the transmission (0.4 / 2), into its command, and the first write passes it to
    the joint's own actuator as it is: the joint leaves home for 0.2 before any controller acts
    (started at its initial_value, its command is that value and it stays). The warning said
    only what the state reads."""
    geared = _transmission(
        '<actuator name="hinge" role="actuator1"/><joint name="hinge" role="joint1">'
        "<mechanical_reduction>2.0</mechanical_reduction></joint>"
    ).replace(
        "<hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin></hardware>",
        "<hardware><plugin>mujoco_ros2_control/MujocoSystemInterface</plugin>"
        '<param name="initial_keyframe">home</param></hardware>',
    )
    result = build_two_link(tmp_path / "keyed", "home: {hinge: 0.4}\n", geared)
    (said,) = [w for w in result.warnings if "to its own actuator" in w]
    assert (
        "so a joint at 0.4 reads 0.2; and started from keyframe 'home', it takes that reading for "
        "the joint's position command, so the joint leaves its start at once (from 0.4 to 0.2), "
        "before any controller acts; in the block"
    ) in said, said


def test_an_override_start_position_file_comes_before_the_initial_keyframe(tmp_path):
    """register_mujoco_actuators loads override_start_position_file first and reads
    initial_keyframe only where the file fails to load: a keyframe the model lacks is then a
    warning, and the start is the file's, not the initial_values the check said."""
    hardware = (
        '<param name="override_start_position_file">/opt/start.xml</param>'
        '<param name="initial_keyframe">start_90</param>'
    )
    result = build_two_link(tmp_path, urdf_extra=control_block(["position"], hardware))
    record = check_record(tmp_path)
    assert record["passes"], record["failures"]
    (said,) = [w for w in result.warnings if "initial_keyframe" in w]
    assert said.startswith(
        "robot.urdf:15: <hardware> param initial_keyframe names keyframe 'start_90', which the "
        "model does not have (its keyframes: 'home'): mujoco_ros2_control stops at start-up "
        '("Failed to apply initial keyframe: \'start_90\'", then "Failed to register MuJoCo '
        'actuators, exiting...") where the override_start_position_file, which it reads first, '
        "fails to load"
    ), said
    # Without an initial_keyframe the start is still the file's, not each joint's initial_value.
    only_file = '<param name="override_start_position_file">/opt/start.xml</param>'
    block = control_block(["position"], only_file)
    away = build_two_link(tmp_path / "file", "home: {hinge: 0.4}\n", block)
    assert not [w for w in away.warnings if "names no initial_keyframe" in w], away.warnings


@pytest.mark.parametrize(
    ("change", "line", "failure"),
    [
        (
            ('name="s" type="system"', 'name="s"'),
            15,
            "<ros2_control> has no type attribute: ros2_control's parser stops the runtime at "
            'start-up ("no attribute type in ros2_control tag"); write type="system" on it',
        ),
        (
            ('<command_interface name="position"/>', "<command_interface/>"),
            15,
            "<command_interface> has no name attribute: ros2_control's parser stops the runtime "
            'at start-up ("no attribute name in command_interface tag"); write name="..." on it',
        ),
        (
            ('<joint name="hinge">', "<joint>"),
            15,
            "<joint> has no name attribute: ros2_control's parser stops the runtime at start-up "
            '("no attribute name in joint tag"); write name="..." on it',
        ),
        (
            ("Interface</plugin>", "Interface</plugin><param>x</param>"),
            15,
            "<param> has no name attribute: ros2_control's parser stops the runtime at start-up "
            '("no parameter name attribute set in param tag"); write name="..." on it',
        ),
        (
            ('<state_interface name="position"/>', '<state_interface name="position"/><limits/>'),
            15,
            "<limits> has no enable attribute: ros2_control's parser stops the runtime at "
            'start-up ("no attribute enable in limits tag"); write enable="true" or '
            'enable="false" on it, or remove it',
        ),
        (
            (
                "</ros2_control>",
                '<transmission name="t"><plugin>transmission_interface/SimpleTransmission'
                '</plugin><joint role="joint1"/><param>x</param></transmission></ros2_control>',
            ),
            15,
            "<joint> has no name attribute: ros2_control's parser stops the runtime at start-up "
            '("no attribute name in joint tag"); write name="..." on it',
        ),
        (
            ("<plugin>mujoco_ros2_control/MujocoSystemInterface</plugin>", ""),
            15,
            "<hardware> has no <plugin>: the parser reads the text of the <plugin> it did not "
            "find: the controller manager crashes at start-up; add "
            "<plugin>mujoco_ros2_control/MujocoSystemInterface</plugin>",
        ),
    ],
)
def test_an_element_without_what_ros2_control_s_parser_reads_stops_the_runtime(
    tmp_path, change, line, failure
):
    """parse_resource_from_xml and the functions it calls read a block's name and type, each
    component's and interface's name, each <param>'s name, each <limits>' enable and the
    <hardware>'s <plugin> without a fallback: a description lacking one stops the controller
    manager. The check passed each of these (a nameless joint was called one the URDF lacks)."""
    block = control_block(["position"])
    old, new = change
    assert old in block, (old, block)
    _fails_to_start(tmp_path, block.replace(old, new, 1))
    failures = check_record(tmp_path)["failures"]
    assert f"robot.urdf:{line}: {failure}" in failures, failures
    if "transmission" not in new:  # one fault, one failure
        assert len(failures) == 1, failures


def test_an_actuator_block_s_transmission_of_two_joints_stops_the_runtime(tmp_path):
    """auto_fill_transmission_interfaces: a block of type "actuator" has exactly one joint in
    each transmission ("There should be exactly one joint defined in this component")."""
    block = control_block(["position"]).replace('type="system"', 'type="actuator"')
    block = block.replace(
        "</ros2_control>",
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        '<joint name="hinge" role="joint1"/><joint name="hinge" role="joint2"/>'
        '<actuator name="hinge" role="actuator1"/></transmission></ros2_control>',
    )
    _fails_to_start(tmp_path, block)
    assert (
        "robot.urdf:15: the transmission of an actuator block has 2 <joint>s: ros2_control's "
        'parser stops the runtime at start-up ("There should be exactly one joint defined in '
        'this component but found 2"); name one joint in it, or make the block type="system"'
    ) in check_record(tmp_path)["failures"]
