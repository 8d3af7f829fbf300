"""``export-urdf --limits-from``: the velocity limits of the URDF a model was made from."""

from __future__ import annotations

from lxml import etree

from tests.conftest import run_cli
from tests.export.handwritten import write_model

# The URDF the hand-written model "came from", reduced to the joints' limits: real ones for
# yaw and finger_a, the placeholders 0 and -1 for pitch and extend, and a joint the model lacks.
ORIGINAL = """<robot name="original">
  <link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/><link name="f"/>
  <joint name="yaw" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-2" upper="2" effort="5" velocity="1.5"/></joint>
  <joint name="pitch" type="revolute"><parent link="b"/><child link="c"/>
    <limit lower="-1" upper="1.5" effort="5" velocity="0"/></joint>
  <joint name="extend" type="prismatic"><parent link="c"/><child link="d"/>
    <limit lower="-0.05" upper="0.1" effort="5" velocity="-1"/></joint>
  <joint name="finger_a" type="prismatic"><parent link="d"/><child link="e"/>
    <limit lower="0" upper="0.02" effort="5" velocity="0.2"/></joint>
  <joint name="gone" type="continuous"><parent link="a"/><child link="f"/>
    <limit effort="5" velocity="9"/></joint>
</robot>
"""


def test_limits_from_the_original_urdf(tmp_path):
    """Real limits are kept (and a coupled joint follows its leader's); placeholders stay
    unknown and the warning names those joints."""
    model = write_model(tmp_path / "model")
    (tmp_path / "original.urdf").write_text(ORIGINAL)
    out = tmp_path / "out" / "robot.urdf"
    args = ["export-urdf", str(model), "-o", str(out), "--no-sites"]
    result = run_cli(*args, "--limits-from", str(tmp_path / "original.urdf"))
    assert result.code == 0, result.stderr
    root = etree.parse(str(out)).getroot()
    velocity = {
        joint.get("name"): joint.find("limit").get("velocity")
        for joint in root.iter("joint")
        if joint.find("limit") is not None
    }
    assert velocity["yaw"] == "1.5" and velocity["finger_a"] == "0.2"
    assert velocity["finger_b"] == "0.2"  # coupled to finger_a, multiplier 1
    assert velocity["pitch"] == velocity["extend"] == "0"
    assert "gone" not in velocity
    warning = next(line for line in result.stderr.splitlines() if "no speed limit" in line)
    assert "pitch" in warning and "extend" in warning and "yaw" not in warning
    without = run_cli(*args)
    assert without.code == 0, without.stderr
    assert 'velocity="1.5"' not in out.read_text()


XACRO = ORIGINAL.replace(
    '<robot name="original">',
    '<robot name="original" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <xacro:arg name="yaw_speed" default="1.5"/>',
).replace('effort="5" velocity="1.5"', 'effort="5" velocity="$(arg yaw_speed)"')


def _velocities(out) -> dict[str, str]:
    root = etree.parse(str(out)).getroot()
    return {
        joint.get("name"): joint.find("limit").get("velocity")
        for joint in root.iter("joint")
        if joint.find("limit") is not None
    }


def test_limits_from_a_xacro_file_expanded_with_its_arguments(tmp_path):
    model = write_model(tmp_path / "model")
    (tmp_path / "original.urdf.xacro").write_text(XACRO)
    out = tmp_path / "out" / "robot.urdf"
    args = ["export-urdf", str(model), "-o", str(out), "--no-sites"]
    source = ["--limits-from", str(tmp_path / "original.urdf.xacro")]
    assert run_cli(*args, *source).code == 0
    assert _velocities(out)["yaw"] == "1.5"  # the argument's default
    result = run_cli(*args, *source, "--xacro-arg", "yaw_speed:=2.5")
    assert result.code == 0, result.stderr
    assert _velocities(out)["yaw"] == "2.5" and _velocities(out)["finger_a"] == "0.2"


def test_limits_from_a_robot_yaml_take_its_source_args(tmp_path):
    model = write_model(tmp_path / "model")
    (tmp_path / "original.urdf.xacro").write_text(XACRO)
    (tmp_path / "robot.yaml").write_text(
        "name: original\nsource:\n  xacro: original.urdf.xacro\n  args: {yaw_speed: '3.5'}\n"
    )
    out = tmp_path / "out" / "robot.urdf"
    args = ["export-urdf", str(model), "-o", str(out), "--no-sites"]
    result = run_cli(*args, "--limits-from", str(tmp_path / "robot.yaml"))
    assert result.code == 0, result.stderr
    assert _velocities(out)["yaw"] == "3.5"


def test_limits_from_a_xacro_file_finding_a_package_take_it_from_the_package_option(tmp_path):
    """A missing package was to be added "under 'packages' in robot.yaml": export-urdf has
    no robot.yaml, and had no way to say where the package is."""
    model = write_model(tmp_path / "model")
    config = tmp_path / "elsewhere" / "cfg"
    (config / "config").mkdir(parents=True)
    (config / "config" / "speeds.yaml").write_text("yaw: 2.25\n")
    (tmp_path / "original.urdf.xacro").write_text(
        XACRO.replace(
            '<xacro:arg name="yaw_speed" default="1.5"/>',
            '<xacro:property name="speeds" value="${xacro.load_yaml(\'$(find cfg)/config/'
            "speeds.yaml')}\"/>",
        ).replace('velocity="$(arg yaw_speed)"', "velocity=\"${speeds['yaw']}\"")
    )
    out = tmp_path / "out" / "robot.urdf"
    args = ["export-urdf", str(model), "-o", str(out), "--no-sites"]
    source = ["--limits-from", str(tmp_path / "original.urdf.xacro")]
    missing = run_cli(*args, *source)
    assert missing.code != 0 and "pass --package cfg=<folder>" in missing.stderr, missing.stderr
    assert "robot.yaml" not in missing.stderr
    result = run_cli(*args, *source, "--package", f"cfg={config}")
    assert result.code == 0, result.stderr
    assert _velocities(out)["yaw"] == "2.25"
