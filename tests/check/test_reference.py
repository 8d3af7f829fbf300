"""The check's reference kinematics come from a reader independent of mjcfbuild's parser."""

from __future__ import annotations

from mjcfbuild.check.model_check import check_model
from mjcfbuild.check.reference import read_kinematics
from mjcfbuild.urdf.model import Pose
from mjcfbuild.urdf.parse import parse_urdf
from tests.check.test_check_command import ROUNDED_MJCF, ROUNDED_URDF
from tests.conftest import write


def _model_of_the_parse(tmp_path, elbow_z: str):
    """The model a build makes of a parse that put the elbow at ``elbow_z``."""
    text = ROUNDED_MJCF.replace("TOOL", '<site name="tool" pos="0 0 -0.2"/>').replace(
        '<body name="lower" pos="0 0 -0.2">', f'<body name="lower" pos="0 0 {elbow_z}">'
    )
    return write(tmp_path / "arm.xml", text)


def test_a_parser_bug_that_the_build_shares_is_caught(tmp_path):
    robot = parse_urdf(ROUNDED_URDF.encode(), "arm.urdf")
    elbow = next(joint for joint in robot.joints if joint.name == "elbow")
    elbow.origin = Pose((0.0, 0.0, -0.3))  # as if the parser misread the elbow's origin
    model = _model_of_the_parse(tmp_path, "-0.3")  # and the build followed the parse
    reference = read_kinematics(ROUNDED_URDF.encode())
    report = check_model(robot, model, model, set(), reference=reference)
    assert report.kinematics.reference == "yourdfpy"
    assert any(f.startswith("link 'lower' is 0.1 m") for f in report.failures), report.failures


def test_the_correct_model_passes_and_an_unreadable_text_falls_back(tmp_path):
    robot = parse_urdf(ROUNDED_URDF.encode(), "arm.urdf")
    model = _model_of_the_parse(tmp_path, "-0.2")
    reference = read_kinematics(ROUNDED_URDF.encode())
    assert check_model(robot, model, model, set(), reference=reference).passes
    fallback = check_model(robot, model, model, set(), reference=read_kinematics(b"<robot"))
    assert fallback.passes
    assert fallback.kinematics.reference.startswith("mjcfbuild's URDF parser")


JOINTED_URDF = """<robot name="jointed">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <link name="e"/>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="a"/>
    <origin xyz="0.1 -0.2 0.3" rpy="0.3 -0.7 1.1"/><axis xyz="0 2 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.5" rpy="1.5 0 0"/><axis xyz="0 0 2"/>
    <limit lower="-0.2" upper="0.3" effort="1" velocity="1"/>
  </joint>
  <joint name="spin" type="continuous">
    <parent link="b"/><child link="c"/><origin xyz="0.2 0 0"/>
  </joint>
  <joint name="follow" type="revolute">
    <parent link="c"/><child link="d"/><origin rpy="0 0 0.4"/><axis xyz="1 0 0"/>
    <mimic joint="turn" multiplier="-0.5" offset="0.1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="bolted" type="fixed">
    <parent link="d"/><child link="e"/><origin xyz="0 0.1 0" rpy="0.2 0.2 0.2"/>
  </joint>
</robot>
"""


def test_the_record_gives_yourdfpys_own_poses_with_unit_axes():
    """yourdfpy's poses, but for its one departure from URDF's meaning, which KDL and MuJoCo
    share: a prismatic joint travels along its unit axis, not a multiple of it (an axis of
    `0 0.7071 0.7071` failed a correct model by 5e-6 m, `1 1 0` by 0.2 m)."""
    import numpy as np
    import yourdfpy

    from mjcfbuild.check.reference import ReferenceKinematics

    text = JOINTED_URDF.encode()
    reference = ReferenceKinematics(read_kinematics(text))
    unit = JOINTED_URDF.replace('<axis xyz="0 0 2"/>', '<axis xyz="0 0 1"/>').encode()
    urdf = yourdfpy.URDF.load(__import__("io").BytesIO(unit), load_meshes=False)
    for values in (
        {"turn": 0.0, "slide": 0.0, "spin": 0.0},
        {"turn": 1.3, "slide": -0.15, "spin": 2.9},
        {"turn": -0.6, "slide": 0.25, "spin": -1.0, "follow": 5.0},  # a mimic follows anyway
    ):
        urdf.update_cfg({k: v for k, v in values.items() if k in urdf.actuated_joint_names})
        poses = reference.poses(values)
        assert set(poses) == {"base", "a", "b", "c", "d", "e"}
        for link, pose in poses.items():
            expected = urdf.get_transform(frame_to=link, frame_from="base")
            assert np.allclose(np.array(pose.rotation), expected[:3, :3], atol=1e-12)
            assert np.allclose(np.array(pose.position), expected[:3, 3], atol=1e-12)


def test_the_digest_follows_the_kinematics_alone():
    from mjcfbuild.check.reference import kinematic_digest

    digest = kinematic_digest(JOINTED_URDF.encode())
    same = [
        JOINTED_URDF.replace('upper="0.3"', 'upper="0.4"'),
        JOINTED_URDF.replace('<child link="c"/>', '<child link="c"/><dynamics damping="2"/>'),
        JOINTED_URDF.replace(
            '<link name="e"/>',
            '<link name="e"><inertial><mass value="1"/>'
            '<inertia ixx="1" iyy="1" izz="1"/></inertial></link>',
        ),
        JOINTED_URDF.replace("<robot", "<!-- a comment -->\n<robot"),
    ]
    for text in same:
        assert kinematic_digest(text.encode()) == digest
    other = [
        JOINTED_URDF.replace('xyz="0.2 0 0"', 'xyz="0.25 0 0"'),
        JOINTED_URDF.replace('<axis xyz="0 0 2"/>', '<axis xyz="0 0 1"/>'),
        JOINTED_URDF.replace('multiplier="-0.5"', 'multiplier="0.5"'),
        JOINTED_URDF.replace('name="spin" type="continuous"', 'name="spin" type="fixed"'),
        JOINTED_URDF.replace('<parent link="d"/>', '<parent link="c"/>'),
        JOINTED_URDF.replace('<link name="e"/>', '<link name="e2"/>'),
    ]
    for text in other:
        assert kinematic_digest(text.encode()) != digest, text


def test_the_cache_key_of_the_reference_is_the_text_without_its_comments():
    """The reader's record is cached by this digest: the comment xacro writes with the
    source's absolute path must not count, anything the reader could read must."""
    from mjcfbuild.check.reference import reader_input_digest

    digest = reader_input_digest(JOINTED_URDF.encode())
    elsewhere = "<!-- autogenerated by xacro from /home/someone/arm.urdf.xacro -->\n"
    assert reader_input_digest((elsewhere + JOINTED_URDF).encode()) == digest
    damped = JOINTED_URDF.replace('<child link="c"/>', '<child link="c"/><dynamics damping="2"/>')
    assert reader_input_digest(damped.encode()) != digest
    entity = '<!DOCTYPE robot [<!ENTITY n "e">]>\n' + JOINTED_URDF.replace('"e"', '"&n;"', 1)
    other = entity.replace('ENTITY n "e"', 'ENTITY n "f"')
    assert reader_input_digest(entity.encode()) != reader_input_digest(other.encode())
    assert reader_input_digest(b"<robot") != reader_input_digest(b"<robot ")


def test_a_damping_edit_does_not_read_the_urdf_again_and_an_origin_edit_does(tmp_path):
    import mjcfbuild
    from tests.conftest import copy_example

    folder = copy_example("arm", tmp_path)
    assert mjcfbuild.build(folder / "robot.yaml", jobs=2).ok
    xacro = folder / "urdf" / "arm.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('damping="0.5"', 'damping="0.6"', 1))
    result = mjcfbuild.build(folder / "robot.yaml", jobs=2)
    assert result.ok and "check" in result.ran and "reference" not in result.ran
    text = xacro.read_text()
    moved = text.replace('xyz="0 0 0.1" axis="0 0 1"', 'xyz="0 0 0.11" axis="0 0 1"', 1)
    assert moved != text, "the example changed: pick another origin"
    xacro.write_text(moved)
    result = mjcfbuild.build(folder / "robot.yaml", jobs=2)
    assert result.ok and "reference" in result.ran
