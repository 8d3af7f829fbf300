"""mjcfbuild's xacro expansion agrees with the ``xacro`` command on every file it can reach.

The reference is the real ``xacro`` command installed with mjcfbuild (xacro 2.1.1 from PyPI),
run as a separate process. Its ``$(find pkg)`` asks ROS 2's ament index, which PyPI does not
ship: ``tests/sources/ament_index`` provides that lookup, and the test lays out an index for the
packages a file needs. The URDFs are compared element by element, attribute by attribute and
text by text; comments and whitespace between elements do not count.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.sources import expand
from mjcfbuild.sources.expand import expand_xacro
from mjcfbuild.sources.packages import PackageResolver
from tests.conftest import EXAMPLES, write

AMENT_INDEX = Path(__file__).parent / "ament_index"
SPELLINGS = (
    "http://www.ros.org/wiki/xacro",
    "http://ros.org/wiki/xacro",
    "http://wiki.ros.org/xacro",
    "urn:any-uri-xacro-accepts",  # xacro goes by the prefix alone
)


def xacro_command(
    source: Path, args: dict[str, str], packages: dict[str, Path], index: Path
) -> subprocess.CompletedProcess:
    """The ``xacro`` command run on ``source``, finding ``packages`` through an ament index
    laid out under ``index``."""
    for name, folder in packages.items():
        marker = index / "share" / "ament_index" / "resource_index" / "packages" / name
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.write_text("")
        (index / "share" / name).symlink_to(folder.resolve(), target_is_directory=True)
    command = Path(sys.executable).with_name("xacro")
    environment = dict(os.environ, AMENT_PREFIX_PATH=str(index), PYTHONPATH=str(AMENT_INDEX))
    arguments = [f"{name}:={value}" for name, value in args.items()]
    return subprocess.run(
        [str(command), str(source), *arguments],
        capture_output=True,
        env=environment,
        cwd=source.parent,
        timeout=120,
    )


def canonical(urdf: bytes) -> tuple:
    """The URDF's elements, attributes and texts, without comments or layout whitespace."""
    from lxml import etree

    parser = etree.XMLParser(
        remove_comments=True, remove_pis=True, remove_blank_text=True, huge_tree=True
    )

    def element(node) -> tuple:
        children = tuple(element(child) for child in node if isinstance(child.tag, str))
        text = (node.text or "").strip()
        return node.tag, tuple(sorted(node.attrib.items())), text, children

    return element(etree.fromstring(urdf, parser))


def assert_agrees(
    source: Path, tmp_path: Path, args: dict[str, str] | None = None, packages=None
) -> bytes | None:
    """Expand ``source`` both ways: both succeed with the same URDF, or both fail. The URDF
    (None where both failed)."""
    args, packages = args or {}, packages or {}
    reference = xacro_command(source, args, packages, tmp_path / "ament")
    try:
        ours = expand_xacro(source, args, PackageResolver(packages, {})).urdf
    except InputError as error:
        assert reference.returncode != 0, (
            f"mjcfbuild refuses what xacro expands: {error}\n{reference.stdout[:400]!r}"
        )
        return None
    assert reference.returncode == 0, (
        f"mjcfbuild expands what xacro refuses: {reference.stderr.decode()[-400:]}"
    )
    assert canonical(ours) == canonical(reference.stdout)
    return ours


MAIN = """<?xml version="1.0" encoding="utf-8"?>
<robot name="r" xmlns:xacro="{ns}">
  <xacro:arg name="width" default="0.1"/>
  <xacro:arg name="with_tool" default="false"/>
  <xacro:property name="cfg" value="${{xacro.load_yaml('$(find pkg)/config/c.yaml')}}"/>
  <xacro:property name="half" value="${{cfg['length'] / 2}}"/>
  <xacro:property name="lazy_block" lazy_eval="true"><origin xyz="0 0 ${{half}}"/></xacro:property>
  <xacro:include filename="$(find pkg)/urdf/parts.xacro" ns="parts"/>
  <xacro:include filename="missing.xacro" optional="true"/>

  <xacro:macro name="link_with" params="name *geometry **extras mass:=1.0 color:=^|grey">
    <link name="${{name}}">
      <inertial><mass value="${{mass}}"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
      <visual>
        <geometry><xacro:insert_block name="geometry"/></geometry>
        <material name="${{color}}"/>
      </visual>
      <xacro:insert_block name="extras"/>
    </link>
  </xacro:macro>

  <xacro:link_with name="base" mass="$(eval 2 * 1.5)">
    <box size="$(arg width) ${{cfg['length']}} 0.1"/>
    <extras><collision><geometry><sphere radius="${{half}}"/></geometry></collision></extras>
  </xacro:link_with>
  <xacro:property name="color" value="blue"/>
  <xacro:call macro="link_with" name="arm">
    <cylinder radius="0.02" length="${{cfg.length}}"/>
    <extras/>
  </xacro:call>
  <xacro:parts.wheel prefix="left" reflect="1"/>
  <xacro:parts.wheel prefix="right" reflect="-1"/>

  <xacro:element xacro:name="joint" name="base_to_arm" type="${{'revolute' if cfg.moving else 'fixed'}}">
    <parent link="base"/><child link="arm"/>
    <xacro:attribute name="doc" value="built by ${{python.str(cfg['length'])}}"/>
    <xacro:insert_block name="lazy_block"/>
    <limit effort="1" velocity="1" lower="${{-pi/2}}" upper="${{radians(90)}}"/>
  </xacro:element>

  <xacro:if value="$(arg with_tool)">
    <link name="tool"/>
  </xacro:if>
  <xacro:unless value="$(arg with_tool)">
    <link name="no_tool"/>
  </xacro:unless>
  <xacro:if value="${{len(cfg['fingers']) > 1}}">
    <link name="${{cfg['fingers'][1]}}"/>
  </xacro:if>
</robot>
"""
PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="{ns}">
  <xacro:macro name="wheel" params="prefix reflect">
    <link name="${{prefix}}_wheel"/>
    <joint name="${{prefix}}_wheel_joint" type="continuous">
      <parent link="base"/><child link="${{prefix}}_wheel"/>
      <origin xyz="0 ${{reflect * 0.2}} 0" rpy="${{pi/2}} 0 0"/>
    </joint>
  </xacro:macro>
</robot>
"""


def write_package(root: Path, ns: str) -> Path:
    """A package using every construct, its files declaring the xacro namespace as ``ns``."""
    write(root / "urdf" / "robot.urdf.xacro", MAIN.format(ns=ns))
    write(root / "urdf" / "parts.xacro", PARTS.format(ns=ns))
    write(root / "config" / "c.yaml", "length: 0.5\nmoving: true\nfingers: [f1, f2]\n")
    return root / "urdf" / "robot.urdf.xacro"


@pytest.mark.parametrize("ns", SPELLINGS)
@pytest.mark.parametrize("args", [{}, {"width": "0.3", "with_tool": "true"}])
def test_every_construct_expands_as_xacro_does_under_every_namespace_spelling(tmp_path, ns, args):
    source = write_package(tmp_path / "pkg", ns)
    urdf = assert_agrees(source, tmp_path, args, {"pkg": tmp_path / "pkg"})
    assert urdf is not None and b'name="right_wheel_joint"' in urdf and b"mjcfbuild" not in urdf
    # The elements still know where they were written, through includes and macros.
    origins = expand_xacro(source, args, PackageResolver({"pkg": tmp_path / "pkg"}, {})).origins
    assert origins and all(line > 0 for _, line in origins.values())
    assert any(file.endswith("parts.xacro") for file, _ in origins.values())


def test_the_wiki_ros_org_spelling_passes_no_parameter_of_ours_to_macros(tmp_path):
    # Two vendors' official descriptions: a macro call whose element the line tracking had
    # marked, so xacro refused it with 'Invalid parameter "mjcfbuild-origin"'.
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://wiki.ros.org/xacro">'
        '<xacro:macro name="m" params="name"><link name="${name}"/></xacro:macro>'
        '<xacro:m name="a"/></robot>',
    )
    expansion = expand_xacro(source, {}, PackageResolver({}, {}))
    assert b'<link name="a"/>' in expansion.urdf
    assert set(expansion.origins.values()) >= {(str(source), 1)}


def test_if_line_tracking_breaks_a_file_the_file_is_expanded_without_it(tmp_path, monkeypatch):
    # The tracking marks elements xacro copies along; should it ever mark one xacro acts on
    # (here: every element, as it once marked the wiki.ros.org spelling's), the expansion
    # that xacro makes on its own is used, untracked, rather than an error blamed on the file.
    monkeypatch.setattr(expand, "is_xacro_element", lambda tag: False)
    source = write_package(tmp_path / "pkg", SPELLINGS[2])
    urdf = assert_agrees(source, tmp_path, {}, {"pkg": tmp_path / "pkg"})
    assert urdf is not None
    expansion = expand_xacro(source, {}, PackageResolver({"pkg": tmp_path / "pkg"}, {}))
    assert expansion.origins == {}


def test_a_file_xacro_refuses_is_refused_saying_xacro_fails_too(tmp_path):
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://wiki.ros.org/xacro">\n'
        '<xacro:macro name="m" params="name"><link name="${name}"/></xacro:macro>\n'
        '<xacro:m name="a" colour="red"/>\n</robot>\n',
    )
    assert assert_agrees(source, tmp_path) is None
    with pytest.raises(InputError, match="called with parameter 'colour'") as caught:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert caught.value.hint == "fix the parameter's name in the call"
    assert caught.value.location is not None and caught.value.location.file == str(source)
    assert caught.value.location.line == 3  # the call, found from xacro's macro stack


@pytest.mark.parametrize(
    "example",
    [
        "arm/urdf/arm.urdf.xacro",
        "arm/urdf/finger.xacro",
        "arm_gripper/gripper/urdf/gripper.urdf.xacro",
    ],
)
def test_the_repositorys_own_xacro_files_expand_as_xacro_does(tmp_path, example):
    packages = {
        "arm_description": EXAMPLES / "arm",
        "gripper_description": EXAMPLES / "arm_gripper" / "gripper",
    }
    assert assert_agrees(EXAMPLES / example, tmp_path, {}, packages) is not None


def wheel_xacro_files() -> list[tuple[Path, dict[str, str], dict[str, Path]]]:
    """Every xacro file of the description wheels the suite downloads, each with no
    arguments and the packages its wheel's files name, and the wheels' xacro robots with the
    arguments they are built with."""
    from bench import other_wheels

    files: list[tuple[Path, dict[str, str], dict[str, Path]]] = []
    wheels = {}
    for robot in other_wheels.ROBOTS.values():
        urdf = other_wheels.unpack(robot)
        wheels[other_wheels.wheel_root(robot.wheel)] = robot.wheel
        if robot.xacro and robot.xacro_args():
            folders = other_wheels.package_folders(robot)
            files.append((urdf, robot.xacro_args(), {k: Path(v) for k, v in folders.items()}))
    for root, wheel in sorted(wheels.items()):
        packages = {k: Path(v) for k, v in other_wheels.wheel_packages(wheel).items()}
        files += [(path, {}, packages) for path in sorted(root.rglob("*.xacro"))]
    return files


@pytest.mark.robots
@pytest.mark.slow
def test_every_xacro_file_of_the_description_wheels_expands_as_xacro_does(tmp_path):
    files = wheel_xacro_files()
    assert len(files) >= 80  # the stretch, stretch4, cookie and roboplan wheels' files
    expanded = 0
    for number, (source, args, packages) in enumerate(files):
        if assert_agrees(source, tmp_path / str(number), args, packages) is not None:
            expanded += 1
    assert expanded >= len(files) - 5  # a few are fragments that only expand when included


@pytest.mark.parametrize(
    ("text", "args", "expands"),
    [
        ("<link name=\"${xacro.arg('base')}\"/>", {"base": "b"}, True),
        ("<link name=\"${xacro.arg('base')}\"/>", {}, False),
        ('<link name="caf\xe9"/>', {}, False),  # written in ISO-8859-1 below
        ('<link name="$(env MJCFBUILD_PARITY_UNSET)"/>', {}, False),
        ('<link name="${1/0}"/>', {}, False),
    ],
    ids=["xacro-arg-given", "xacro-arg-missing", "iso-8859-1", "unset-env", "division"],
)
def test_what_xacro_takes_and_refuses_at_the_edges(tmp_path, monkeypatch, text, args, expands):
    """The cases this project once decided apart from the xacro command: an argument read
    with xacro.arg, a file that is not UTF-8, failures outside macros."""
    monkeypatch.delenv("MJCFBUILD_PARITY_UNSET", raising=False)
    source = tmp_path / "r.xacro"
    source.write_bytes(
        (
            '<?xml version="1.0" encoding="ISO-8859-1"?>\n'
            '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f'  <link name="root"/>\n  {text}\n</robot>\n'
        ).encode("latin-1")
    )
    assert (assert_agrees(source, tmp_path, args) is not None) == expands


NESTED_MACROS = (
    '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '<xacro:macro name="foot" params="side">\n'
    '  <link name="${side}_foot_${missing}"/>\n'
    "</xacro:macro>\n"
    '<xacro:macro name="leg" params="side">\n'
    '  <link name="${side}_hip"/>\n'
    '  <xacro:foot side="${side}"/>\n'
    "</xacro:macro>\n"
    '<link name="root"/>\n'
    '<xacro:leg side="left"/>\n'
    "</robot>\n"
)


def test_a_failure_in_a_macro_is_placed_in_the_macro_xacro_names(tmp_path):
    """xacro's trace names the innermost macro and its file ("when instantiating macro: foot
    (r.xacro)"); mjcfbuild names the same macro, at the line of the expression that failed."""
    import re

    source = write(tmp_path / "r.xacro", NESTED_MACROS)
    theirs = xacro_command(source, {}, {}, tmp_path / "index")
    assert theirs.returncode != 0
    trace = theirs.stderr.decode()
    macro = re.search(r"when instantiating macro: (\S+) \((\S+)\)", trace)
    assert macro is not None, trace
    with pytest.raises(InputError) as caught:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert f"in macro '{macro.group(1)}'" in caught.value.message
    location = caught.value.location
    assert location is not None and Path(location.file) == Path(macro.group(2))
    assert location.line == 3  # ${missing}, inside foot


def test_an_include_cycle_xacro_recurses_through_is_named_at_the_include_closing_it(tmp_path):
    """xacro recurses until Python's stack runs out, naming the files it went through;
    mjcfbuild names the cycle at the include that closes it, one of those files."""
    write(
        tmp_path / "a.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:include filename="b.xacro"/>\n</robot>\n',
    )
    source = tmp_path / "a.xacro"
    write(
        tmp_path / "b.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:include filename="a.xacro"/>\n</robot>\n',
    )
    theirs = xacro_command(source, {}, {}, tmp_path / "index")
    assert theirs.returncode != 0
    trace = theirs.stderr.decode()
    assert "maximum recursion depth exceeded" in trace and str(tmp_path / "b.xacro") in trace
    with pytest.raises(InputError, match=r"include cycle: a\.xacro includes b\.xacro") as caught:
        expand_xacro(source, {}, PackageResolver({}, {}))
    location = caught.value.location
    assert location is not None and (Path(location.file), location.line) == (
        tmp_path / "b.xacro",
        2,
    )


def test_an_argument_of_a_file_included_under_a_false_condition_is_taken(tmp_path):
    """xacro takes `finger_len:=0.08` when the file declaring it is included only under a
    condition that is false; mjcfbuild said no file declared it (it looked only at the files
    xacro read). A misspelt name is still refused."""
    from mjcfbuild.errors import ManifestError

    pkg = tmp_path / "pkg"
    write(pkg / "package.xml", "<package><name>pkg</name></package>\n")
    write(
        pkg / "urdf" / "main.urdf.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="cond">\n'
        '  <xacro:arg name="with_gripper" default="true"/>\n'
        '  <link name="base"/>\n'
        '  <xacro:if value="$(arg with_gripper)">\n'
        '    <xacro:include filename="$(find pkg)/urdf/gripper.xacro"/>\n'
        "  </xacro:if>\n"
        "</robot>\n",
    )
    write(
        pkg / "urdf" / "gripper.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="finger_len" default="0.05"/>\n'
        '  <link name="finger"><visual><geometry><box size="0.01 0.01 $(arg finger_len)"/>'
        "</geometry></visual></link>\n"
        "</robot>\n",
    )
    source = pkg / "urdf" / "main.urdf.xacro"
    args = {"with_gripper": "false", "finger_len": "0.08"}
    assert xacro_command(source, args, {"pkg": pkg}, tmp_path / "ament").returncode == 0
    resolver = PackageResolver({"pkg": pkg}, {})
    expand_xacro(source, args, resolver, args_key="robot.yaml source.args")
    assert_agrees(source, tmp_path / "again", args, {"pkg": pkg})
    with pytest.raises(ManifestError, match="did you mean 'finger_len'"):
        expand_xacro(source, {"finger_lne": "0.08"}, resolver, args_key="robot.yaml source.args")


@pytest.mark.parametrize(
    "data",
    [
        # Declared ISO-8859-1, written in UTF-8: xacro reads text as UTF-8 whatever the
        # declaration says (read as bytes, the names came out 'arm_Ã¼').
        '<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="r" '
        'xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="arm_\u00fc"/></robot>\n',
        # Declared US-ASCII with a UTF-8 comment: refused as bytes, taken by xacro.
        '<?xml version="1.0" encoding="us-ascii"?>\n<!-- J\u00fcrgen -->\n<robot name="r" '
        'xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/></robot>\n',
        # An entity declaration named in a comment declares nothing.
        '<!-- never use <!ENTITY declarations here -->\n<robot name="r" '
        'xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/></robot>\n',
    ],
    ids=["declared-latin1", "declared-ascii", "entity-in-comment"],
)
def test_declarations_that_do_not_change_what_xacro_reads(tmp_path, data):
    source = tmp_path / "r.urdf.xacro"
    source.write_bytes(data.encode("utf-8"))
    assert assert_agrees(source, tmp_path) is not None


def test_arguments_xacro_takes_without_a_declaration_here_are_taken(tmp_path):
    """An argument read by its bare name in $(eval), and one declared only in a file a false
    condition includes by an expression: the xacro command takes both; they were refused as
    undeclared. A misspelling of a declared name is still refused."""
    from mjcfbuild.errors import ManifestError

    write(
        tmp_path / "gazebo.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="gazebo_controllers" default=""/></robot>\n',
    )
    source = write(
        tmp_path / "r.urdf.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="use_gazebo" default="false"/>\n'
        '  <xacro:property name="here" value="${xacro.abs_filename(\'.\')}"/>\n'
        '  <xacro:if value="$(arg use_gazebo)">\n'
        '    <xacro:include filename="${here}/gazebo.xacro"/>\n'
        "  </xacro:if>\n"
        '  <link name="base"/><link name="arm"/><link name="$(eval \'tool_\' + side)"/>\n'
        '  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>\n'
        '    <limit effort="1" velocity="1" lower="$(eval -1.0 * joint_range)" '
        'upper="$(eval joint_range)"/></joint>\n'
        "</robot>\n",
    )
    args = {"joint_range": "2.5", "gazebo_controllers": "/tmp/c.yaml", "side": "left"}
    assert assert_agrees(source, tmp_path / "both", args) is not None
    resolver = PackageResolver({}, {})
    expand_xacro(source, args, resolver, args_key="robot.yaml source.args")
    # Four edits from 'use_gazebo', and a name the skipped file may declare: taken, as the
    # xacro command takes it (it had been refused as a misspelling of 'use_gazebo').
    wider = {**args, "use_gazebo_gui": "true"}
    assert assert_agrees(source, tmp_path / "gui", wider) is not None
    expand_xacro(source, wider, resolver, args_key="robot.yaml source.args")
    with pytest.raises(ManifestError, match="did you mean 'use_gazebo'"):
        misspelt = {"joint_range": "2.5", "side": "left", "use_gazeb": "true"}
        expand_xacro(source, misspelt, resolver, args_key="robot.yaml source.args")


ARGS = (
    '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <xacro:arg name="prefix" default="def_"/>\n'
    '  <xacro:arg name="flag" default="false"/>\n'
    '  <link name="$(arg prefix)base"/>\n'
    "  <link name=\"${xacro.arg('prefix')}tool\"/>\n"
    '  <xacro:if value="$(arg flag)"><link name="flagged"/></xacro:if>\n'
    "</robot>\n"
)


def test_argument_values_are_stripped_of_spaces_as_the_xacro_command_strips_them(tmp_path):
    """The xacro command strips NAME:=VALUE's value (load_mappings); robot.yaml's " sp_ "
    was passed with its spaces (a link named " sp_base", a flag " true " xacro refuses)."""
    source = write(tmp_path / "r.urdf.xacro", ARGS)
    urdf = assert_agrees(source, tmp_path, {"prefix": " sp_ ", "flag": " true\t"})
    assert urdf is not None
    assert b'name="sp_base"' in urdf and b'name="sp_tool"' in urdf and b"flagged" in urdf


def test_an_empty_argument_value_is_ignored_as_the_xacro_command_ignores_it(tmp_path):
    """``xacro f.xacro prefix:=`` leaves the default ("if src and dst" in load_mappings);
    robot.yaml's prefix: "" was passed as ''. Which default applied is recorded (a
    warning says it), where it is not empty."""
    source = write(tmp_path / "r.urdf.xacro", ARGS)
    urdf = assert_agrees(source, tmp_path, {"prefix": "", "flag": " "})
    assert urdf is not None and b'name="def_base"' in urdf and b"flagged" not in urdf
    expansion = expand_xacro(source, {"prefix": "", "flag": "true"}, PackageResolver({}, {}))
    assert expansion.ignored_args == {"prefix": "def_"}


CHAIN = (
    '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <xacro:macro name="chain" params="n">\n'
    '    <xacro:if value="${n > 0}">\n'
    '      <link name="c${n}"/>\n'
    '      <xacro:chain n="${n-1}"/>\n'
    "    </xacro:if>\n"
    "  </xacro:macro>\n"
    '  <link name="c"/>\n'
    '  <xacro:chain n="{depth}"/>\n'
    "</robot>\n"
)


@pytest.mark.parametrize("depth", [247, 248])
def test_a_recursive_macro_fails_at_the_depth_the_xacro_command_fails_at(tmp_path, depth):
    """The xacro command expands a macro calling itself 247 levels deep and fails at 248 (its
    Python's recursion limit); mjcfbuild's own calls below xacro took some of that limit, so
    246 levels failed here, with an error saying xacro fails the same way."""
    source = write(tmp_path / "r.urdf.xacro", CHAIN.replace("{depth}", str(depth)))
    theirs = xacro_command(source, {}, {}, tmp_path / "index")
    assert (theirs.returncode == 0) == (depth == 247), "xacro's own limit moved: find it again"
    assert_agrees(source, tmp_path)
