"""MuJoCo's warnings are kept for the build, not printed or logged to MUJOCO_LOG.TXT."""

from __future__ import annotations

import mujoco

from mjcfbuild.mjwarnings import capture_mujoco_warnings, take_mujoco_warnings

# MuJoCo's URDF import warns about a limit with lower == upper (and ignores it).
EMPTY_RANGE = """<robot name="r"><link name="a"/>
<link name="b"><inertial><mass value="1"/>
<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
<limit lower="0" upper="0" effort="1" velocity="1"/></joint></robot>"""


def test_warnings_are_collected_and_no_log_file_is_written(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    capture_mujoco_warnings()
    take_mujoco_warnings()
    mujoco.MjModel.from_xml_string(EMPTY_RANGE)
    assert take_mujoco_warnings() == ["joint 'j' has equal lower and upper limits, limit ignored"]
    assert take_mujoco_warnings() == []
    assert list(tmp_path.iterdir()) == []
    assert "WARNING" not in capfd.readouterr().out
