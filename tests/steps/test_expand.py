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
