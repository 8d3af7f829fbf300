"""The digest of what decides an MJCF part's contacts: joint dynamics, actuators and sensors
leave it unchanged, geoms and bodies do not."""

from __future__ import annotations

import json

from mjcfbuild.selfcollision.parts import collision_digest
from tests.conftest import write

PART = """<mujoco><worldbody><body name="palm">
  <geom type="box" size="0.02 0.05 0.015" rgba="{rgba}"/>
  <body name="finger"><joint name="j" type="slide" damping="{damping}"/>
    <geom type="box" size="{size} 0.006 0.02"/></body>
</body></worldbody>
<actuator><position name="a" joint="j" kp="{kp}"/></actuator></mujoco>"""


def digest(tmp_path, name, damping=1, kp=100, size=0.01, rgba="1 0 0 1", home=0.0):
    xml = write(tmp_path / f"{name}.xml", PART.format(damping=damping, kp=kp, size=size, rgba=rgba))
    summary = write(
        tmp_path / f"{name}.json",
        json.dumps({"bodies": ["palm", "finger"], "home_qpos": {"j": [home]}, "warnings": [name]}),
    )
    return collision_digest(xml, summary)


def test_only_what_decides_contacts_counts(tmp_path):
    base = digest(tmp_path, "a")
    assert digest(tmp_path, "b", damping=3, kp=500, rgba="0 1 0 1") == base
    assert digest(tmp_path, "c", size=0.012) != base
    assert digest(tmp_path, "d", home=0.02) != base
    assert collision_digest(tmp_path / "missing.xml", tmp_path / "a.json").startswith("unreadable")
