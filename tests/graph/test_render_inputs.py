"""Previews are redrawn only when what they show changed."""

from __future__ import annotations

import json
from pathlib import Path

import mjcfbuild
from mjcfbuild.graph.hashes import HashCache
from mjcfbuild.graph.render_inputs import render_digest
from tests.conftest import write

MODEL = """<mujoco model="m">
  <option timestep="0.002"/>
  <worldbody>
    <body name="b" pos="0 0 1">
      <inertial pos="0 0 0" mass="1" diaginertia="0.1 0.1 0.1"/>
      <joint name="j" damping="0.5" range="-1 1"/>
      <geom type="mesh" mesh="m" rgba="1 0 0 1"/>
    </body>
  </worldbody>
  <actuator><position joint="j" kp="10"/></actuator>
</mujoco>
"""


def digest(folder: Path, text: str) -> str | None:
    write(folder / "m.xml", text)
    return render_digest(folder / "m.xml", folder / "assets", HashCache(None))


def test_dynamics_do_not_change_the_digest_and_looks_do(tmp_path):
    write(tmp_path / "assets" / "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    base = digest(tmp_path, MODEL)
    assert base is not None
    unseen = (
        ('damping="0.5"', 'damping="2"'),
        ('range="-1 1"', 'range="-2 2"'),
        ('mass="1"', 'mass="3"'),
        ('kp="10"', 'kp="50"'),
        ('timestep="0.002"', 'timestep="0.001"'),
    )
    for old, new in unseen:
        assert digest(tmp_path, MODEL.replace(old, new)) == base, new
    seen = (('pos="0 0 1"', 'pos="0 0 2"'), ('rgba="1 0 0 1"', 'rgba="0 1 0 1"'))
    for old, new in seen:
        assert digest(tmp_path, MODEL.replace(old, new)) != base, new
    write(tmp_path / "assets" / "m.obj", "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n")
    assert digest(tmp_path, MODEL) != base
    assert digest(tmp_path, "<mujoco") is None


def test_a_damping_change_reruns_the_check_but_not_the_previews(arm):
    manifest = arm / "robot.yaml"
    assert "previews" in mjcfbuild.build(manifest, jobs=2).ran
    xacro = arm / "urdf" / "arm.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('damping="0.5"', 'damping="0.7"', 1))
    ran = set(mjcfbuild.build(manifest, jobs=2).ran)
    assert {"assemble", "check"} <= ran and "previews" not in ran
    mesh = arm / "meshes" / "finger.stl"
    data = bytearray(mesh.read_bytes())
    data[84 + 12] ^= 0x01
    mesh.write_bytes(bytes(data))
    assert "previews" in mjcfbuild.build(manifest, jobs=2).ran  # a shape changed: redrawn


def test_a_visual_mesh_edit_redraws_the_visual_pictures_only(arm):
    manifest = arm / "robot.yaml"
    mjcfbuild.build(manifest, jobs=2)
    record = arm / "mjcf" / ".mjcfbuild" / "previews.json"
    before = json.loads(record.read_text())
    assert sorted(before) == [
        "closeup_collision.png",
        "closeup_visual.png",
        "side_collision.png",
        "side_visual.png",
        "three_quarter_collision.png",
        "three_quarter_visual.png",
        "top_visual.png",
    ]
    mesh = arm / "meshes" / "base.stl"  # the base's collision geometry is a cylinder
    data = bytearray(mesh.read_bytes())
    data[84 + 12] ^= 0x01
    mesh.write_bytes(bytes(data))
    assert "previews" in mjcfbuild.build(manifest, jobs=2).ran
    after = json.loads(record.read_text())
    for name in before:
        assert (after[name] == before[name]) == ("collision" in name), name
