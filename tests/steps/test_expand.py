"""The ``expand`` step's warnings, seen through whole builds of small xacro sources."""

from __future__ import annotations

import mjcfbuild
from tests.conftest import INERTIA, write

XACRO = f"""<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="prefix" default="def_"/>
  <xacro:arg name="suffix" default=""/>
  <link name="$(arg prefix)base$(arg suffix)">{INERTIA}
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
</robot>
"""


def build(folder, manifest: str):
    """Build ``manifest`` (robot.yaml's text) in ``folder``, without the check."""
    write(folder / "robot.yaml", manifest)
    return mjcfbuild.build(folder / "robot.yaml", jobs=1, check=False)


def test_an_empty_argument_is_ignored_for_its_default_and_said_at_its_robot_yaml_line(tmp_path):
    """The xacro command ignores prefix:= (the default applies); it was passed as ''. Where
    the default is empty too, nothing changes and nothing is said."""
    write(tmp_path / "r.urdf.xacro", XACRO)
    manifest = "name: r\nsource:\n  xacro: r.urdf.xacro\n  args:\n    prefix: ''\n    suffix: ''\n"
    result = build(tmp_path, manifest)
    assert b'name="def_base"' in (tmp_path / "mjcf" / ".mjcfbuild" / "source.urdf").read_bytes()
    said = [warning for warning in result.warnings if "empty value" in warning]
    assert said == [
        "robot.yaml:5: source.args.prefix: the empty value is ignored, as the xacro command "
        "ignores 'prefix:='; the default 'def_' applies (give a value, or leave the argument "
        "out)"
    ]


PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="rungs" params="count">
    <xacro:property name="pi" value="3"/>
    <link name="rung_${len(range(count))}"/><joint name="j${count}" type="fixed">
      <parent link="base"/><child link="rung_${count}"/></joint>
  </xacro:macro>
</robot>
"""

WARNED = f"""<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="urdf/parts.xacro"/>
  <link name="base">{INERTIA}
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
  <xacro:rungs count="2"/>
  <xacro:rungs count="3"/>
  <link name="${{xacro.warning('calibrate me')}}tip"/><joint name="jt" type="fixed">
    <parent link="base"/><child link="tip"/></joint>
</robot>
"""


def test_xacros_warnings_are_build_warnings_at_their_file_and_line(tmp_path, capfd):
    """xacro's warnings were only in the expand step's log; each is now a build warning, once,
    marked as xacro's, at the line of the macro body (in its file) where xacro warned."""
    write(tmp_path / "urdf" / "parts.xacro", PARTS)
    write(tmp_path / "r.urdf.xacro", WARNED)
    result = build(tmp_path, "name: r\nsource:\n  xacro: r.urdf.xacro\n")
    said = [warning for warning in result.warnings if "xacro warns" in warning]
    assert said == [
        "urdf/parts.xacro:4: xacro warns (in macro 'rungs'): redefining global symbol: pi",
        "urdf/parts.xacro:5: xacro warns (in macro 'rungs'): Using range() directly is "
        "deprecated. Use python.range() instead.",
        "r.urdf.xacro: xacro warns: calibrate me",
    ]
    assert "redefining" not in capfd.readouterr().err
