"""ros2_control: cameras and lidars matched to their sensors (actuators: tests/control)."""

from __future__ import annotations

import mjcfbuild
from tests.conftest import two_link_urdf, write

CONTROL = """<ros2_control name="sim" type="system">
  <joint name="hinge">
    <command_interface name="position"/><command_interface name="velocity"/>
    <state_interface name="position"><param name="initial_value">0.5</param></state_interface>
  </joint>
  <sensor name="front_camera"><param name="image_topic">/img</param></sensor>
</ros2_control>"""


def build(tmp_path, manifest_extra: str, control: str = CONTROL):
    write(tmp_path / "robot.urdf", two_link_urdf(extra=control))
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + manifest_extra)
    # The assembly's warnings; the check fails a camera sensor without its camera on top
    # (tests/check/test_runtime.py), which would stop the build before they are returned.
    return mjcfbuild.build(tmp_path / "robot.yaml", check=False)


def test_cameras_and_sensors_without_partners_are_warned_both_ways(tmp_path):
    result = build(tmp_path, "mujoco_inputs:\n  cameras: [{name: wrist_camera, link: arm}]\n")
    assert any(
        "camera 'wrist_camera' has no ros2_control <sensor name='wrist_camera'> "
        "(ros2_control sensors: front_camera)" in w
        for w in result.warnings
    )
    assert any(
        "ros2_control camera sensor 'front_camera' has no MuJoCo camera of its name" in w
        for w in result.warnings
    )


def test_a_ros1_transmission_naming_a_joint_the_urdf_lacks_is_warned_at_its_line(tmp_path):
    """Issue 43: never ignored in silence, and no advice to name the missing joint in an
    actuator rule (the reduction would need a motor there)."""
    transmission = (
        '<transmission name="t"><type>transmission_interface/SimpleTransmission</type>\n'
        '<joint name="hinj"><hardwareInterface>hardware_interface/EffortJointInterface'
        '</hardwareInterface></joint>\n<actuator name="m"><mechanicalReduction>50'
        "</mechanicalReduction></actuator></transmission>"
    )
    result = build(
        tmp_path,
        "actuators:\n  rules:\n    - {joints: [hinge], motor: go1_knee}\n",
        control=transmission,
    )
    line = (
        (tmp_path / "robot.urdf")
        .read_text()
        .splitlines()
        .index(
            '<joint name="hinj">'
            "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>"
        )
    )
    assert (
        f"robot.urdf:{line + 1}: <transmission> #1 names joint 'hinj', which the URDF does not "
        "have, so it is ignored; did you mean 'hinge'?"
    ) in result.warnings, result.warnings
    assert not [w for w in result.warnings if "hinj" in w and "rules" in w], result.warnings


def test_transmission_reductions_are_read_from_ros1_and_ros2_control():
    from lxml import etree

    from mjcfbuild.inputs.ros2_control import read_ros2_control

    urdf = b"""<robot name="r">
  <transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
    <joint name="knee"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><mechanicalReduction>-9</mechanicalReduction></actuator></transmission>
  <transmission name="t2">
    <joint name="hip"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m2"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
  <ros2_control name="hw" type="system">
    <joint name="elbow"><command_interface name="position"/></joint>
    <transmission name="t3"><plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="m3" role="actuator1"/>
      <joint name="elbow" role="joint1"><mechanical_reduction>50</mechanical_reduction></joint>
    </transmission>
    <transmission name="t4"><plugin>transmission_interface/SimpleTransmission</plugin>
      <param name="mechanical_reduction">100</param><joint name="wrist" role="joint1"/>
    </transmission>
  </ros2_control>
</robot>"""
    control = read_ros2_control(etree.fromstring(urdf), "robot.urdf")
    reductions = {t.joint: t.reduction for t in control.transmissions}
    # A negative reduction only flips the direction; 1 is the usual placeholder: no gearbox.
    assert reductions == {"knee": 9.0, "hip": None, "elbow": 50.0, "wrist": 100.0}
    assert next(t for t in control.transmissions if t.joint == "elbow").origin == "robot.urdf:12"
    # What else each joint's transmission holds, in both dialects.
    drives = {t.joint: (t.actuators, t.element, t.kind) for t in control.transmissions}
    simple = "transmission_interface/SimpleTransmission"
    assert drives == {
        "knee": (["m1"], "#1", simple),
        "hip": (["m2"], "#2", ""),
        "elbow": (["m3"], "#3", simple),
        "wrist": ([], "#4", simple),
    }
    assert [t.commands() for t in control.transmissions] == [True, True, True, True]


def test_a_transmission_names_its_actuators_and_its_type_in_either_form():
    from lxml import etree

    from mjcfbuild.inputs.ros2_control import read_ros2_control

    urdf = b"""<robot name="r">
  <transmission name="wrist"><type>transmission_interface/DifferentialTransmission</type>
    <actuator name="m7"/><actuator name="m6"/><actuator/>
    <joint name="pitch"><hardwareInterface>JointStateInterface</hardwareInterface></joint>
    <joint name="roll"/></transmission>
  <transmission name="old" type="pr2_mechanism_model/SimpleTransmission">
    <joint name="a"/><actuator name="m1"/></transmission>
</robot>"""
    control = read_ros2_control(etree.fromstring(urdf), "robot.urdf")
    found = [(t.joint, t.actuators, t.element, t.kind, t.commands()) for t in control.transmissions]
    assert found == [
        (
            "pitch",
            ["m7", "m6"],
            "#1",
            "transmission_interface/DifferentialTransmission",
            False,
        ),
        (
            "roll",
            ["m7", "m6"],
            "#1",
            "transmission_interface/DifferentialTransmission",
            True,
        ),
        ("a", ["m1"], "#2", "pr2_mechanism_model/SimpleTransmission", True),
    ]


def test_a_plan_an_earlier_version_wrote_is_read_without_its_removed_fields():
    """`mjcfbuild check` reads the plan a build left; one written before a joint's `pids`
    field was removed stopped it with a TypeError."""
    from mjcfbuild.inputs.ros2_control import Ros2Control

    control = Ros2Control.from_dict(
        {
            "joints": [
                {"name": "j", "commands": ["position"], "initial": None, "origin": "", "pids": True}
            ]
        }
    )
    assert control.joints[0].name == "j" and control.joints[0].plugin == ""


def test_a_blocks_transmission_keeps_what_ros2_controls_parser_reads():
    """The block it is in, the joint's own signed reduction and offset (what SimpleTransmission
    applies; the actuator's is not read), and the elements without a role."""
    from lxml import etree

    from mjcfbuild.inputs.ros2_control import read_ros2_control

    urdf = b"""<robot name="r">
  <ros2_control name="a" type="system"><joint name="knee"/></ros2_control>
  <ros2_control name="b" type="system">
    <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="m" role="actuator1"><mechanical_reduction>7</mechanical_reduction></actuator>
      <joint name="elbow"><offset>0.25</offset><mechanical_reduction>-2</mechanical_reduction>
      </joint>
      <joint name="wrist" role="joint2"><mechanical_reduction>two</mechanical_reduction></joint>
    </transmission>
  </ros2_control>
</robot>"""
    control = read_ros2_control(etree.fromstring(urdf), "robot.urdf")
    found = [
        (t.joint, t.block, t.joint_reduction, t.joint_offset, t.roleless)
        for t in control.transmissions
    ]
    assert found == [
        ("elbow", 1, -2.0, 0.25, ["joint 'elbow'"]),
        ("wrist", 1, 1.0, 0.0, ["joint 'elbow'"]),
    ]
