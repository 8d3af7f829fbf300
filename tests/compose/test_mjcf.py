"""MJCF parts on their own: reading and normalising a part (degrees, includes, inertia from
geoms, assets by content), attaching it with MjSpec, and the check against the part alone."""

from __future__ import annotations

import json
from pathlib import Path

import mujoco
import pytest
import trimesh
from lxml import etree

from mjcfbuild.check.parts import PartReference, check_part
from mjcfbuild.compose.attach import AttachedPart, attach_parts
from mjcfbuild.compose.mjcf import PartSummary
from mjcfbuild.errors import InputError, ManifestError
from mjcfbuild.mjcf.precise import precise_xml
from mjcfbuild.steps import mjcfpart

# Degrees, Euler angles, an include, inertia from geoms, one mesh file under two names.
PART = """<mujoco model="claw">
  <compiler angle="degree" meshdir="parts" eulerseq="xyz"/>
  <option cone="elliptic"/>
  <include file="classes.xml"/>
  <asset>
    <mesh name="a" file="a.stl"/>
    <mesh name="b" file="b.stl" scale="1 2 1"/>
  </asset>
  <worldbody>
    <body name="base" euler="10 20 30" pos="0.01 0 0.02">
      <geom class="hard" type="mesh" mesh="a"/>
      <body name="jaw" pos="0 0.03 0.05" axisangle="0 0 1 45">
        <joint name="hinge" axis="1 0 0" range="-30 60"/>
        <geom class="hard" type="mesh" mesh="b"/>
        <body name="tip" pos="0 0 0.04">
          <joint name="ball" type="ball"/>
          <geom class="hard" size="0.01"/>
        </body>
      </body>
    </body>
  </worldbody>
  <tendon><fixed name="t"><joint joint="hinge" coef="1"/></fixed></tendon>
  <actuator><position name="close" tendon="t" kp="5"/></actuator>
  <keyframe>
    <key name="home" qpos="0.5 1 0 0 0" ctrl="0.5"/>
    <key name="open" qpos="1 1 0 0 0"/>
  </keyframe>
</mujoco>
"""
CLASSES = """<mujoco><default><default class="hard"><geom type="box" size="0.01 0.02 0.03"
  density="800"/></default></default></mujoco>"""
ARM = """<mujoco><compiler angle="radian" inertiafromgeom="false"/><worldbody>
  <body name="link"><joint name="arm" axis="0 0 1"/>
    <inertial pos="0 0 0" mass="1" diaginertia="0.1 0.1 0.1"/><geom size="0.05"/>
    <site name="flange" pos="0 0 0.3" quat="0 1 0 0"/></body></worldbody></mujoco>"""


@pytest.fixture
def part(tmp_path: Path) -> dict:
    """A part written to disk, read by the mjcfpart step; its payload."""
    folder = tmp_path / "claw"
    (folder / "parts").mkdir(parents=True)
    cube = trimesh.creation.box(extents=[0.02, 0.02, 0.02]).export(file_type="stl")
    (folder / "parts" / "a.stl").write_bytes(cube)
    (folder / "parts" / "b.stl").write_bytes(cube)  # the same bytes: one published file
    (folder / "claw.xml").write_text(PART)
    (folder / "classes.xml").write_text(CLASSES)
    state = tmp_path / "state"
    payload = {
        "source": str(folder / "claw.xml"),
        "label": "claw/claw.xml",
        "xml": str(state / "0.mjcf.xml"),
        "summary": str(state / "0.mjcf.json"),
        "depfile": str(state / "0.mjcf.deps.json"),
        "assets_dir": str(state / "assets"),
    }
    payload["result"] = mjcfpart.run(dict(payload))
    return payload


def test_a_part_is_summarised_with_its_files_home_and_driven_joints(part):
    summary = PartSummary.from_dict(json.loads(Path(part["summary"]).read_text()))
    folder = Path(part["source"]).parent
    assert set(summary.files) == {
        str(folder / "claw.xml"),
        str(folder / "classes.xml"),
        str(folder / "parts" / "a.stl"),
        str(folder / "parts" / "b.stl"),
    }
    assert set(part["result"]["discovered"]) == set(summary.files) - {part["source"]}
    assert len(summary.assets) == 1  # two mesh files with the same content
    assert [j.name for j in summary.joints if j.actuated] == ["hinge"]  # through the tendon
    assert summary.home_qpos == {"hinge": [0.5], "ball": [1.0, 0.0, 0.0, 0.0]}
    assert summary.home_ctrl == {"close": 0.5} and summary.home_source == "keyframe 'home'"
    warnings = " ".join(summary.warnings)
    assert "'open'" in warnings and "cone" in warnings


def attached(part: dict, to: str, pos=(0.0, 0.0, 0.1), quat=(1.0, 0.0, 0.0, 0.0)):
    """The example arm with the part attached, written and loaded again as the build does."""
    spec = mujoco.MjSpec.from_string(ARM)
    summary = PartSummary.from_dict(json.loads(Path(part["summary"]).read_text()))
    entry = AttachedPart("robot.yaml attach[0]", "c_", to, pos, quat, Path(part["xml"]), summary)
    published = attach_parts(spec, {}, [entry])
    assert list(published.values()) == list(summary.assets.values())
    return mujoco.MjModel.from_xml_string(etree.tostring(precise_xml(spec), encoding="unicode"))


@pytest.mark.parametrize("to", ["link", "flange"])
def test_the_attached_part_matches_the_part_alone(part, to):
    quat = (0.5, 0.5, 0.5, 0.5)
    model = attached(part, to, quat=quat)
    reference = PartReference("c_", Path(part["source"]), "claw.xml", to, (0, 0, 0.1), quat)
    result = check_part(model, reference, configurations=5, seed=1, tolerance=1e-9)
    assert result.missing == [] and result.problems == []
    assert result.max_position_error < 1e-12 and result.max_rotation_error < 1e-9
    # Degrees became radians at full precision, inertia from geoms became explicit.
    assert model.jnt_range[model.joint("c_hinge").id][1] == pytest.approx(
        1.0471975511966, rel=1e-11
    )
    assert model.body_mass[model.body("c_jaw").id] > 0


def test_the_check_finds_a_part_away_from_where_it_belongs(part):
    model = attached(part, "flange", pos=(0.0, 0.0, 0.1))
    misplaced = PartReference(
        "c_", Path(part["source"]), "claw.xml", "flange", (0, 0, 0.2), (1, 0, 0, 0)
    )
    result = check_part(model, misplaced, configurations=3, seed=0, tolerance=1e-9)
    assert result.max_position_error == pytest.approx(0.1)
    wrong = PartReference(
        "x_", Path(part["source"]), "claw.xml", "flange", (0, 0, 0.1), (1, 0, 0, 0)
    )
    assert "body 'x_base'" in check_part(model, wrong, 1, 0, 1e-9).missing


def test_a_prefix_making_a_name_collide_names_the_setting(part):
    spec = mujoco.MjSpec.from_string(ARM.replace('name="link"', 'name="c_jaw"'))
    summary = PartSummary.from_dict(json.loads(Path(part["summary"]).read_text()))
    entry = AttachedPart(
        "robot.yaml attach[0]", "c_", "c_jaw", (0, 0, 0), (1, 0, 0, 0), Path(part["xml"]), summary
    )
    with pytest.raises(ManifestError, match="'c_jaw'") as caught:
        attach_parts(spec, {}, [entry])
    assert caught.value.location.file == "robot.yaml attach[0].prefix"


@pytest.mark.parametrize(
    ("change", "message", "line"),
    [
        (('<joint name="ball" type="ball"/>', '<freejoint name="loose"/>'), "free joint", None),
        (('mesh="b"', 'mesh="nothing"'), "mesh 'nothing' not found", 14),
        (("</worldbody>", "</worldbdy>"), "XML error", None),
    ],
)
def test_a_part_that_fails_alone_names_its_file(part, change, message, line):
    source = Path(part["source"])
    source.write_text(PART.replace(*change))
    with pytest.raises(InputError, match=message) as caught:
        mjcfpart.run({k: v for k, v in part.items() if k != "result"})
    assert caught.value.location.file == "claw/claw.xml"
    if line is not None:
        assert caught.value.location.line == line
