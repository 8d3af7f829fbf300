"""A joint's limits mean one thing in the build and in its check: wheels turn freely."""

from __future__ import annotations

from lxml import etree

from mjcfbuild.errors import EXIT_OK
from tests.conftest import run_cli, simple_manifest, write

WHEEL_INERTIA = '<inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>'


def wheeled_urdf() -> str:
    """A base on two wheels, each described the way wheeled robots do: effort and velocity only."""
    wheels = ""
    for side, y in (("left", 0.2), ("right", -0.2)):
        wheels += f"""
  <link name="{side}_wheel">{WHEEL_INERTIA}
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.1" length="0.04"/></geometry></collision>
  </link>
  <joint name="{side}_wheel_joint" type="revolute">
    <parent link="base"/><child link="{side}_wheel"/><origin xyz="0 {y} 0"/>
    <axis xyz="0 1 0"/><limit effort="5" velocity="20"/>
  </joint>"""
    return f"""<?xml version="1.0"?>
<robot name="rover">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>{wheels}
</robot>
"""


def test_a_wheel_without_bounds_builds_unlimited_and_passes_the_check(tmp_path):
    write(tmp_path / "robot.urdf", wheeled_urdf())
    simple_manifest(tmp_path)
    result = run_cli("build", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    # Both wheels' warnings are one line on the console; the report lists each.
    (warning,) = [line for line in result.stderr.splitlines() if "without lower or upper" in line]
    assert "2 × revolute joint" in warning and "left_wheel_joint, right_wheel_joint" in warning
    report = (tmp_path / "mjcf" / "report" / "report.md").read_text()
    listed = [line for line in report.splitlines() if line.startswith("- ") and "lower or" in line]
    assert len(listed) == 2 and "left_wheel_joint" in listed[0]
    model = etree.parse(str(tmp_path / "mjcf" / "robot.xml"))
    for joint in model.iter("joint"):
        assert joint.get("range") is None, etree.tostring(joint)
        assert joint.get("limited") in (None, "false")


def test_one_bound_given_means_the_other_is_zero():
    from mjcfbuild.urdf.limits import joint_range
    from mjcfbuild.urdf.parse import parse_urdf

    urdf = wheeled_urdf().replace(
        '<limit effort="5" velocity="20"/>', '<limit upper="0.5" effort="5" velocity="20"/>', 1
    )
    robot = parse_urdf(urdf.encode(), "robot.urdf")
    ranges = {j.name: joint_range(j) for j in robot.joints}
    assert ranges == {"left_wheel_joint": (0.0, 0.5), "right_wheel_joint": None}
