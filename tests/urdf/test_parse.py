"""Parsing URDF bytes: the model, and errors with file and line for every defect."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.urdf.model import robot_from_dict
from mjcfbuild.urdf.parse import parse_urdf
from tests.conftest import two_link_urdf


def parse(text: str):
    return parse_urdf(text.encode(), "r.urdf")


def error_of(text: str) -> InputError:
    with pytest.raises(InputError) as info:
        parse(text)
    return info.value


def test_two_link_robot():
    robot = parse(two_link_urdf())
    assert robot.name == "two_link"
    assert robot.root == "base"
    joint = robot.joints[0]
    assert (joint.kind, joint.parent, joint.child, joint.axis) == (
        "revolute",
        "base",
        "arm",
        (0, 1, 0),
    )
    assert joint.limit.lower == -1.5 and joint.limit.upper == 1.5
    assert joint.origin.rpy == (0, 0, 0.3)
    arm = robot.link("arm")
    assert arm.visuals[0].material.rgba == (1, 0, 0, 1)
    assert arm.collisions[0].geometry.size == (0.03, 0.5)
    assert arm.visuals[0].line is not None


def test_round_trip_through_json():
    robot = parse(two_link_urdf())
    assert robot_from_dict(robot.to_dict()) == robot


def test_encoding_declaration_is_accepted():
    assert parse('<?xml version="1.0" encoding="UTF-8"?>\n<robot name="a"><link name="l"/></robot>')


def test_an_xml_declaration_after_blank_lines_is_read_with_a_warning():
    # pybullet_data's biped2d_pybullet.urdf; MuJoCo's URDF import and pybullet read it.
    text = (
        '\n\n\n<?xml version="1.0"?>\n<robot name="a">\n<link name="l"/>\n<link name="l"/></robot>'
    )
    assert error_of(text).location.line == 7  # every element keeps its line
    robot = parse(text.replace('<link name="l"/></robot>', "</robot>"))
    assert [link.name for link in robot.links] == ["l"]
    assert robot.warnings == [
        "r.urdf:4: the XML declaration follows blank lines; read as if it came first "
        "(remove what precedes it)"
    ]


@pytest.mark.parametrize(
    ("after", "read"),
    [
        ("\n</robot>\n", True),  # PyFlyt's rocket.urdf
        ("</robot> what follows is never read <", True),
        ('\n  </other a="1">\n', True),
        ("\ntext\n", False),  # MuJoCo's parser refuses these as lxml does
        ("\n</ robot>\n", False),
        ("\n<extra>\n", False),
    ],
)
def test_a_closing_tag_after_the_root_is_read_where_mujoco_reads_it(after, read):
    import mujoco

    text = '<robot name="a">\n<link name="l"/>\n</robot>' + after
    try:
        mujoco.MjModel.from_xml_string(text)
        mujoco_reads = True
    except ValueError:
        mujoco_reads = False
    assert mujoco_reads == read
    if not read:
        assert "Extra content" in error_of(text).message
        return
    robot = parse(text)
    assert [link.name for link in robot.links] == ["l"]
    line = 3 if after.startswith("<") else 4
    assert robot.warnings == [
        f"r.urdf:{line}: a closing tag {after.strip().split('>')[0]}> after the root "
        "element's end; ignored with what follows it, as MuJoCo's and urdfdom's parser "
        "(tinyxml2) read the first root element only (remove it)"
    ]


def test_an_xml_declaration_of_another_version_is_read_as_1_0_with_a_warning():
    # pybullet_data's bicycle/bike.urdf says version="0.0".
    robot = parse('<?xml version=\'0.0\' ?>\n<robot name="a"><link name="l"/></robot>')
    assert robot.name == "a"
    assert robot.warnings == [
        'r.urdf:1: the XML declaration says version "0.0"; read as 1.0 (write version="1.0")'
    ]
    assert parse('<?xml version="1.1"?>\n<robot name="a"><link name="l"/></robot>').warnings == []


def test_a_declared_encoding_the_utf_8_bytes_are_not_in_is_read_as_utf_8_with_a_warning():
    """ROS's and MuJoCo's parsers read every URDF as UTF-8: a name with an accent came out
    another name here ('arm_\u00c3\u00bc'), obeying the declaration."""
    text = '<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="a"><link name="arm_\u00fc"/></robot>'
    robot = parse_urdf(text.encode("utf-8"), "r.urdf")
    assert [link.name for link in robot.links] == ["arm_\u00fc"]
    assert robot.warnings == [
        'r.urdf:1: the XML declaration says encoding="ISO-8859-1" but the file is UTF-8; read '
        "as UTF-8, as ROS's and MuJoCo's URDF parsers read it (write encoding=\"UTF-8\")"
    ]
    latin = parse_urdf(text.encode("latin-1"), "r.urdf")  # truly ISO-8859-1: as declared
    assert [link.name for link in latin.links] == ["arm_\u00fc"] and latin.warnings == []


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-le", "utf-32"])
def test_a_urdf_in_utf_16_or_32_is_read_with_its_nul_bytes(encoding):
    # Their characters hold NUL bytes, the last ones after the root element included.
    declared = encoding.upper().removesuffix("-LE")
    text = (
        f'<?xml version="1.0" encoding="{declared}"?>\n<robot name="a"><link name="l"/></robot>\n'
    )
    robot = parse_urdf(text.encode(encoding), "r.urdf")
    assert [link.name for link in robot.links] == ["l"] and robot.warnings == []


def test_nul_bytes_after_the_root_element_are_dropped_with_a_warning():
    # pybullet_data's humanoid/humanoid.urdf ends in a NUL byte (a C string's terminator).
    robot = parse('<robot name="a">\r\n<link name="l"/>\r\n</robot>\r\n\x00\x00')
    assert [link.name for link in robot.links] == ["l"]
    assert robot.warnings == ["r.urdf:4: NUL bytes after the end of the XML; ignored (remove them)"]
    assert "malformed XML" in error_of('<robot name="a">\x00<link name="l"/></robot>').message


def test_an_undeclared_world_parent_is_the_ground_with_a_warning():
    # drake's Acrobot.urdf welds its base to a 'world' it never declares, as Drake allows
    robot = parse(
        '<robot name="a"><link name="base"/>\n<joint name="weld" type="fixed">'
        '<parent link="world"/><child link="base"/></joint></robot>'
    )
    assert [link.name for link in robot.links] == ["world", "base"]
    assert robot.root == "world"
    assert robot.warnings == [
        "r.urdf:2: joint 'weld' has the parent link 'world', which the URDF does not declare: "
        'taken as the ground, as Drake reads it (add <link name="world"/> for the readers '
        "that refuse it: ROS's urdfdom, MuJoCo's own import)"
    ]
    # any other undeclared link stays an error, and a declared world gets no second one
    assert (
        "link 'ground', which does not exist"
        in error_of(
            '<robot><link name="b"/><joint name="j" type="fixed">'
            '<parent link="ground"/><child link="b"/></joint></robot>'
        ).message
    )
    declared = parse(
        two_link_urdf(
            extra='<link name="world"/><joint name="w" type="fixed">'
            '<parent link="world"/><child link="base"/></joint>'
        )
    )
    assert [link.name for link in declared.links].count("world") == 1 and not declared.warnings


def test_a_spherical_joint_says_how_to_write_it_in_urdf():
    error = error_of(
        "<robot name='r'><link name='a'/><link name='b'/>\n<joint name='j' type='spherical'>"
        "<parent link='a'/><child link='b'/></joint></robot>"
    )
    assert error.hint is not None and error.hint.endswith(
        "'spherical' is pybullet's extension, not URDF: write the ball joint as three revolute "
        "joints through two small links"
    )


def test_text_before_the_xml_declaration_is_still_malformed():
    assert "malformed XML" in error_of('x\n<?xml version="1.0"?>\n<robot name="a"/>').message


def test_named_global_materials_are_resolved():
    robot = parse(
        '<robot name="a"><material name="blue"><color rgba="0 0 1 1"/></material>'
        '<link name="l"><visual><geometry><sphere radius="1"/></geometry>'
        '<material name="blue"/></visual></link></robot>'
    )
    assert robot.link("l").visuals[0].material.rgba == (0, 0, 1, 1)


def test_commas_between_numbers_are_repaired_with_a_warning():
    robot = parse(two_link_urdf().replace('rpy="0 0 0.3"', 'rpy="0, 0, 0.3"'))
    assert robot.joints[0].origin.rpy == (0, 0, 0.3)
    assert any("commas" in w for w in robot.warnings)


def test_undeclared_namespace_prefix_is_a_warning():
    robot = parse(two_link_urdf(extra='<drake:joint name="x" type="ball"/>'))
    assert any("drake" in w for w in robot.warnings)
    assert [j.name for j in robot.joints] == ["hinge"]


# Each defect: the URDF text, what the error says (the test's id), and the line it names.
DEFECTS = [
    ("<robot><link name='a'>\n</robot>", "malformed XML", 2),
    ("<model name='x'/>", "root element is <model>", 1),
    ("<robot name='a'/>", "no links", 1),
    ("<robot>\n<link name='a'/>\n<link name='a'/>\n</robot>", "link 'a' is defined twice", 3),
    (
        "<robot><link name='a'/><link name='b'/>\n<joint name='j' type='fixed'>"
        "<parent link='a'/><child link='c'/></joint></robot>",
        "refers to link 'c', which does not exist",
        2,
    ),
    (
        "<robot><link name='a'/><link name='b'/>\n<joint name='j' type='spherical'>"
        "<parent link='a'/><child link='b'/></joint></robot>",
        "unknown type 'spherical'",  # pybullet_data's humanoid.urdf
        2,
    ),
    (
        "<robot><link name='a'/><link name='b'/><link name='c'/>\n"
        "<joint name='j' type='fixed'><parent link='a'/><child link='b'/></joint></robot>",
        "2 root links",
        1,
    ),
    (  # the extra root is named where it is written, before the robot's own or after it
        "<robot>\n<link name='extra'/>\n<link name='a'/><link name='b'/>"
        "<joint name='j' type='fixed'><parent link='a'/><child link='b'/></joint></robot>",
        "2 root links (extra, a)",
        2,
    ),
    (
        "<robot><link name='a'/><link name='b'/>\n"
        "<joint name='j1' type='fixed'><parent link='a'/><child link='b'/></joint>\n"
        "<joint name='j2' type='fixed'><parent link='b'/><child link='a'/></joint></robot>",
        "cycle",
        2,
    ),
    (
        "<robot><link name='a'>\n<visual><geometry><cone radius='1'/></geometry></visual>"
        "</link></robot>",
        "unknown geometry <cone>",
        2,
    ),
    (
        "<robot><link name='a'>\n<visual><geometry><box size='1 1'/></geometry></visual>"
        "</link></robot>",
        "needs 3 numbers, found 2",
        2,
    ),
    (
        "<robot><link name='a'>\n<visual><geometry><box size='1 nan 1'/></geometry></visual>"
        "</link></robot>",
        "not a finite number",
        2,
    ),
    (
        "<robot><link name='a'>\n<inertial><mass value='x'/></inertial></link></robot>",
        "'x' is not a number",
        2,
    ),
    (
        "<robot><link name='a'/><link name='b'/>\n<joint name='j' type='revolute'>"
        "<parent link='a'/><child link='b'/><axis xyz='0 0 0'/></joint></robot>",
        "zero axis",
        2,
    ),
    # Python's float() reads these; C's strtod, and so urdfdom (ROS), does not.
    (
        "<robot><link name='a'>\n<inertial><mass value='1_000'/></inertial></link></robot>",
        "'1_000' is not a number",
        2,
    ),
    (
        "<robot><link name='a'>\n<visual><geometry><box size='1 \u0661 1'/></geometry>"
        "</visual></link></robot>",
        "'\u0661' is not a number",
        2,
    ),
    # A missing bound is 0 (URDF, urdfdom): lower 1 alone is an empty range.
    (
        "<robot><link name='a'/><link name='b'/><joint name='j' type='revolute'>"
        "<parent link='a'/><child link='b'/>\n<limit lower='1' effort='1' velocity='1'/>"
        "</joint></robot>",
        "lower limit 1 above its upper limit 0 (it gives no upper",
        2,
    ),
    (
        "<robot><link name='a'/><link name='b'/>\n<joint name='j' type='revolute'>"
        "<parent link='a'/><child link='b'/><mimic joint='k'/></joint></robot>",
        "mimics joint 'k', which does not exist",
        2,
    ),
    (
        "<robot><link name='a'/><link name='b'/><link name='c'/>\n"
        "<joint name='f' type='fixed'><parent link='a'/><child link='b'/></joint>\n"
        "<joint name='j' type='revolute'><parent link='b'/><child link='c'/>"
        "<limit lower='-1' upper='1' effort='1' velocity='1'/><mimic joint='f'/></joint></robot>",
        "joint 'j' mimics joint 'f', which is fixed",
        3,
    ),
    (
        "<robot><link name='a'/><link name='b'/><link name='c'/>\n"
        "<joint name='l' type='continuous'><parent link='a'/><child link='b'/>"
        "<mimic joint='r'/></joint>\n"
        "<joint name='r' type='continuous'><parent link='a'/><child link='c'/>"
        "<mimic joint='l'/></joint></robot>",
        "joints l -> r -> l mimic each other in a ring, so none of them is driven",
        2,
    ),
]


def test_a_fixed_joint_may_mimic_a_fixed_joint():
    """It moves nothing either way (genesis' panda with a suction cup fixes both fingers)."""
    robot = parse_urdf(
        b"<robot name='r'><link name='a'/><link name='b'/><link name='c'/>"
        b"<joint name='f1' type='fixed'><parent link='a'/><child link='b'/></joint>"
        b"<joint name='f2' type='fixed'><parent link='a'/><child link='c'/>"
        b"<mimic joint='f1'/></joint></robot>",
        "r.urdf",
    )
    assert [joint.name for joint in robot.joints] == ["f1", "f2"]


@pytest.mark.parametrize(("text", "message", "line"), DEFECTS, ids=[d[1] for d in DEFECTS])
def test_defects_are_errors_with_lines(text, message, line):
    error = error_of(text)
    assert message in error.message
    assert error.location.file == "r.urdf"
    assert error.location.line == line


def test_two_roots_of_equal_trees_name_the_extra_one_not_the_robots_own():
    # base and c each carry one child: base, written first, is the robot's; c is the extra.
    # Before: "connect 'base' ... to the robot".
    chain = "<joint name='{j}' type='fixed'><parent link='{p}'/><child link='{c}'/></joint>"
    text = (
        "<robot>\n<link name='base'/>\n<link name='a'/>\n<link name='c'/>\n<link name='d'/>\n"
        + chain.format(j="j1", p="base", c="a")
        + chain.format(j="j2", p="c", c="d")
        + "</robot>"
    )
    from mjcfbuild.errors import InputError

    with pytest.raises(InputError) as refused:
        parse(text)
    assert refused.value.location is not None and refused.value.location.line == 4
    assert refused.value.hint == (
        "connect 'c' to the robot (below 'base') with a joint, or remove it"
    )


def test_every_extra_root_is_named():
    links = "".join(f"<link name='{name}'/>" for name in ("x", "base", "a", "y"))
    joint = "<joint name='j' type='fixed'><parent link='base'/><child link='a'/></joint>"
    from mjcfbuild.errors import InputError

    with pytest.raises(InputError) as refused:
        parse(f"<robot>{links}{joint}</robot>")
    assert refused.value.hint == (
        "connect 'x', 'y' to the robot (below 'base') with a joint, or remove them"
    )


def test_an_unreadable_axis_of_a_fixed_or_floating_joint_is_ignored_with_a_warning():
    # urdfdom (ROS) reads no axis there; a moving joint's axis must still be a number.
    for kind in ("fixed", "floating"):
        robot = parse_urdf(
            b"<robot name='r'><link name='a'/><link name='b'/><joint name='j' type='"
            + kind.encode()
            + b"'><parent link='a'/><child link='b'/>\n<axis xyz='0 0 1_0'/></joint></robot>",
            "r.urdf",
        )
        assert robot.joints[0].axis == (1.0, 0.0, 0.0)
        assert robot.warnings == [
            "r.urdf:2: <axis> xyz=\"0 0 1_0\": '1_0' is not a number; ignored, as a "
            f"{kind} joint has no axis (remove the <axis>)"
        ]


def test_entity_declarations_are_refused():
    text = (
        '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY big "AAAA">]>'
        '<robot name="&big;"><link name="a"/></robot>'
    )
    error = error_of(text)
    assert "entity declarations are not allowed" in error.message
    assert error.location.line == 2


@pytest.mark.parametrize("value", ["true", "auto"])
def test_masses_from_the_geometry_are_said_not_to_be_applied(value):
    """MuJoCo's import of this URDF computes the link's mass from its box (0.32 kg); the model
    had 0.1 g, without a word."""
    robot = parse_urdf(
        (
            '<robot name="a">\n<mujoco>\n'
            f'<compiler inertiafromgeom="{value}"/></mujoco><link name="b"/></robot>'
        ).encode(),
        "a.urdf",
    )
    assert robot.warnings == [
        f'a.urdf:3: <compiler inertiafromgeom="{value}"> is not applied: mjcfbuild takes each '
        "link's mass and inertia from its <inertial> alone (a link without one gets a "
        "placeholder mass); give each link its <inertial>"
    ]
    quiet = parse_urdf(
        b'<robot name="a"><mujoco><compiler inertiafromgeom="false"/></mujoco><link name="b"/>'
        b"</robot>",
        "a.urdf",
    )
    assert quiet.warnings == []


def test_existing_mujoco_compiler_is_kept_for_merging():
    robot = parse(
        '<robot name="a"><mujoco><compiler balanceinertia="true" meshdir="x"/></mujoco>'
        '<link name="l"/></robot>'
    )
    assert robot.mujoco_compiler == {"balanceinertia": "true", "meshdir": "x"}


def test_a_name_defined_twice_says_where_first_and_a_missing_one_lists_the_others():
    twice = error_of("<robot>\n<link name='a'/>\n<link name='a'/>\n</robot>")
    assert twice.message == "link 'a' is defined twice (first at line 2)"
    assert twice.hint == "rename one of them, or remove it"
    mimic = error_of(
        "<robot><link name='a'/><link name='b'/>\n<joint name='j' type='revolute'>"
        "<parent link='a'/><child link='b'/><mimic joint='k9'/></joint></robot>"
    )
    assert mimic.hint == "joints: j"  # nothing close to 'k9': the joints there are


@pytest.mark.parametrize("kind", ["revolute", "prismatic"])
def test_a_joint_urdfdom_refuses_for_want_of_a_limit_is_warned_of(kind):
    robot = parse(
        "<robot><link name='a'/><link name='b'/>\n"
        f"<joint name='j' type='{kind}'><parent link='a'/><child link='b'/></joint></robot>"
    )
    assert [w for w in robot.warnings if "without <limit>" in w] == [
        f"r.urdf:2: joint 'j' is {kind} without <limit>: ROS's URDF parser (urdfdom) refuses "
        "it, MuJoCo's import makes it unlimited; add <limit lower= upper= effort= velocity=/>, "
        'or make it type="continuous"'
        + (" (a prismatic joint cannot be)" if kind == "prismatic" else "")
    ]
    continuous = parse(
        "<robot><link name='a'/><link name='b'/>\n"
        "<joint name='j' type='continuous'><parent link='a'/><child link='b'/></joint></robot>"
    )
    assert not [w for w in continuous.warnings if "without <limit>" in w]


def test_a_missing_link_is_not_matched_to_one_that_merely_shares_letters():
    """atlas_v3's neck_ry names a link 'head' the file lacks: 'did you mean r_hand?' sent the
    user the wrong way (the URDF reader kept its own difflib call)."""
    urdf = (
        '<robot name="r"><link name="base"/><link name="r_hand"/><link name="l_hand"/>'
        '<joint name="a" type="fixed"><parent link="base"/><child link="r_hand"/></joint>'
        '<joint name="b" type="fixed"><parent link="base"/><child link="l_hand"/></joint>'
        '<joint name="neck_ry" type="fixed"><parent link="base"/><child link="head"/></joint>'
        "</robot>"
    )
    with pytest.raises(InputError) as info:
        parse_urdf(urdf.encode(), "r.urdf")
    assert "head" in info.value.message and "did you mean" not in (info.value.hint or "")


def _mujoco_reads(data: bytes, tmp_path) -> bool:
    """Whether MuJoCo's URDF import reads ``data`` from a file (tinyxml2 takes its bytes)."""
    import mujoco

    path = tmp_path / "robot.urdf"
    path.write_bytes(data)
    try:
        mujoco.MjModel.from_xml_path(str(path))
    except ValueError:
        return False
    return True


ROBOT = b'<robot name="a">\n<link name="l"/>\n</robot>\n'


@pytest.mark.parametrize(
    ("after", "read"),
    [
        (b'<robot name="b"><link name="m"/></robot>\n', True),
        (b"<!-- a comment -->\n<other/>\n<!-- and another -->\n", True),
        (b'<robot name="b"><link name="m">\n', False),  # unclosed: tinyxml2 refuses it too
        (b"<other/>\ntext\n", False),
    ],
)
def test_a_second_root_element_is_ignored_where_mujoco_reads_the_first(after, read, tmp_path):
    data = ROBOT + after
    assert _mujoco_reads(data, tmp_path) == read
    if not read:
        with pytest.raises(InputError, match="Extra content"):
            parse_urdf(data, "r.urdf")
        return
    robot = parse_urdf(data, "r.urdf")
    assert [link.name for link in robot.links] == ["l"]
    tag = "other" if b"<other" in after else "robot"
    line = 5 if after.startswith(b"<!--") else 4
    assert robot.warnings == [
        f"r.urdf:{line}: a second root element <{tag}> after the root element's end; ignored "
        "with what follows it, as MuJoCo's and urdfdom's parser (tinyxml2) read the first root "
        "element only (remove it)"
    ]


def test_an_element_before_the_robot_is_refused_as_mujoco_refuses_it(tmp_path):
    data = b"<other/>\n" + ROBOT
    assert not _mujoco_reads(data, tmp_path)
    with pytest.raises(InputError, match="the root element is <other>"):
        parse_urdf(data, "r.urdf")


@pytest.mark.parametrize(
    "data",
    [
        ROBOT + b"<!-- a comment after the root -->\n",
        b"\xef\xbb\xbf" + ROBOT,  # a UTF-8 byte order mark
        b'\xef\xbb\xbf<?xml version="1.0" encoding="utf-8"?>\n' + ROBOT,
    ],
)
def test_a_comment_after_the_root_and_a_byte_order_mark_are_read_as_mujoco_reads_them(
    data, tmp_path
):
    assert _mujoco_reads(data, tmp_path)
    robot = parse_urdf(data, "r.urdf")
    assert [link.name for link in robot.links] == ["l"] and robot.warnings == []


@pytest.mark.parametrize(
    ("data", "line", "more"),
    [
        (ROBOT.replace(b"</robot>", b'<note text="caf\xe9"/>\n</robot>'), 3, ""),
        (ROBOT.replace(b"</robot>", b"<!-- caf\xe9 na\xefve -->\n</robot>"), 3, " (and 1 more)"),
        (b'<?xml version="1.0" encoding="UTF-8"?>\n' + ROBOT.replace(b'"l"', b'"l\xe9"'), 3, ""),
    ],
)
def test_a_latin_1_byte_is_read_as_latin_1_where_mujoco_reads_the_file(data, line, more, tmp_path):
    """tinyxml2 takes bytes as they are; libxml2 refused the file ("Invalid bytes in character
    encoding")."""
    assert _mujoco_reads(data, tmp_path)
    robot = parse_urdf(data, "r.urdf")
    assert [link.name for link in robot.links] in (["l"], ["l\u00e9"])
    assert robot.warnings == [
        f"r.urdf:{line}: byte 0xe9 is not UTF-8{more}; read as Latin-1 ('\u00e9'), as MuJoCo's "
        "and urdfdom's parser (tinyxml2) read the file without a word (save it as UTF-8)"
    ]


def test_an_instruction_after_the_start_is_read_with_a_warning_that_mujoco_refuses_it(tmp_path):
    """tinyxml2 takes every <?...?> for a declaration, which only the start may hold: MuJoCo
    refuses the file, where libxml2 reads it without the instruction."""
    leading = b'<?xml version="1.0"?>\n<?xml-model href="urdf.xsd"?>\n' + ROBOT
    assert _mujoco_reads(leading, tmp_path)
    assert parse_urdf(leading, "r.urdf").warnings == []
    for data, line in (
        (ROBOT + b'<?xml-stylesheet href="s.css"?>\n', 4),
        (ROBOT.replace(b"<link", b"<?xml-stylesheet?>\n<link"), 2),
        (b"<!-- header -->\n<?xml-model?>\n" + ROBOT, 2),
    ):
        assert not _mujoco_reads(data, tmp_path)
        robot = parse_urdf(data, "r.urdf")
        assert [link.name for link in robot.links] == ["l"]
        tag = data.split(b"<?")[1].split(b" ")[0].split(b"?")[0].decode()
        assert robot.warnings == [
            f"r.urdf:{line}: <?{tag} ...?> after the start of the file is read without it here, "
            "but MuJoCo's and urdfdom's parser (tinyxml2) refuse the file there (remove it, or "
            "move it before everything else)"
        ]
    # One in a comment is text.
    assert parse_urdf(ROBOT + b"<!-- <?pi?> -->\n", "r.urdf").warnings == []


def test_a_malformed_xml_declaration_is_read_without_it_as_mujoco_reads_the_file(tmp_path):
    # urdf-usd-converter's simple_box_no_material.urdf: `<?xml verison="1.0"?>`. tinyxml2 skips
    # a declaration unread; libxml2 refused the whole file ("expecting version").
    data = b'<?xml verison="1.0"?>\n' + ROBOT
    assert _mujoco_reads(data, tmp_path)
    robot = parse_urdf(data, "r.urdf")
    assert [link.name for link in robot.links] == ["l"]
    assert robot.warnings == [
        "r.urdf:1: the XML declaration is malformed (Malformed declaration expecting version); "
        "read without it, as MuJoCo's and ROS's URDF parsers read the file (write "
        '<?xml version="1.0"?>)'
    ]


def test_a_late_instruction_is_warned_of_once_however_often_the_file_is_read_again(tmp_path):
    # A Latin-1 byte makes the reader read the file a second time; the warning stays one.
    data = ROBOT.replace(b'name="l"', b'name="l" x="\xe9"') + b"<?pi?>\n"
    robot = parse_urdf(data, "r.urdf")
    assert sum("<?pi ...?>" in warning for warning in robot.warnings) == 1


def test_a_late_xml_declaration_is_refused_without_a_warning_that_it_is_read():
    # libxml2 refuses it ("XML declaration allowed only at the start"), so the warning that
    # the file is read without it would contradict the error that follows.
    from mjcfbuild.urdf.parse import parse_xml

    warnings: list[str] = []
    with pytest.raises(InputError, match="XML declaration allowed only at the start"):
        parse_xml(b'<!-- c -->\n<?xml version="1.0"?>\n' + ROBOT, "r.urdf", warnings)
    assert warnings == []


def test_a_latin_1_control_byte_is_named_not_printed():
    # Windows-1252's curly quote 0x92 is a control character in Latin-1: printed as it is, the
    # warning carried an invisible character.
    robot = parse_urdf(ROBOT.replace(b"</robot>", b"<!-- it\x92s -->\n</robot>"), "r.urdf")
    assert "byte 0x92 is not UTF-8; read as Latin-1 (U+0092)," in robot.warnings[0]
