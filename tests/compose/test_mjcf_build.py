"""The arm_mjcf_gripper example: a hand-tuned MJCF hand attached to the example arm with its
own actuator, tendon, equality, sensors and home; robot.yaml rules and home naming its prefixed
joints; the check comparing it with the hand alone; rebuilds per part; bad attachments."""

from __future__ import annotations

import filecmp
import json

import mujoco
import numpy as np
import pytest

import mjcfbuild
from mjcfbuild.errors import EXIT_INPUT, EXIT_MANIFEST, EXIT_OK
from tests.conftest import copy_example, run_cli

OVERRIDES = """actuators:
  rules:
    - {joints: ["hand_*"], damping: 3}
home:
  elbow: 0.6
  hand_*_finger: 0.03
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The example with robot.yaml naming the hand's joints in a rule and in home."""
    folder = copy_example("arm_mjcf_gripper", tmp_path_factory.mktemp("built"))
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("home:\n  elbow: 0.6\n", OVERRIDES))
    result = mjcfbuild.build(manifest, jobs=2)
    assert result.ok, result
    return folder, result, mujoco.MjModel.from_xml_path(str(result.robot))


def test_the_hand_keeps_its_actuator_tendon_equality_and_sensors_prefixed(built):
    _, _, model = built
    grip = model.actuator("hand_grip")
    assert model.actuator_trntype[grip.id] == mujoco.mjtTrn.mjTRN_TENDON
    assert model.actuator_trnid[grip.id][0] == model.tendon("hand_split").id
    assert {model.sensor(i).name for i in range(model.nsensor)} >= {
        "hand_left_finger_pos",
        "hand_opening",
    }
    assert model.neq == 2  # the arm's finger mimic and the hand's own coupling
    # No second actuator on the hand's joints: the rule gave them damping only.
    driven = [
        model.actuator(i).name
        for i in range(model.nu)
        if model.actuator_trntype[i] == mujoco.mjtTrn.mjTRN_JOINT
        and model.joint(model.actuator_trnid[i][0]).name.startswith("hand_")
    ]
    assert driven == []
    assert model.dof_damping[model.joint("hand_left_finger").dofadr[0]] == 3.0
    # The hand's default classes, prefixed; its geoms keep their classes' types.
    palm = model.body("hand_palm").id
    types = {int(model.geom_type[g]) for g in range(model.ngeom) if model.geom_bodyid[g] == palm}
    assert types == {
        mujoco.mjtGeom.mjGEOM_MESH,
        mujoco.mjtGeom.mjGEOM_BOX,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
    }


def test_home_takes_robot_yaml_for_hand_joints_and_the_servo_aims_there(built):
    _, _, model = built
    home = model.key("home")
    for joint in ("hand_left_finger", "hand_right_finger"):
        assert home.qpos[model.joint(joint).qposadr[0]] == pytest.approx(0.03)
    assert home.qpos[model.joint("elbow").qposadr[0]] == pytest.approx(0.6)
    assert home.ctrl[model.actuator("hand_grip").id] == pytest.approx(0.03)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, home.id)
    for _ in range(500):
        mujoco.mj_step(model, data)
    assert np.all(np.isfinite(data.qpos))
    assert data.qpos[model.joint("hand_left_finger").qposadr[0]] == pytest.approx(0.03, abs=2e-3)


def test_assets_are_published_by_content_and_the_check_covers_the_hand(built):
    folder, _, _ = built
    output = folder / "mjcf"
    text = (output / "arm_with_mjcf_hand.xml").read_text()
    assert str(folder) not in text and "hand/assets" not in text
    stl = sorted(p.name for p in (output / "assets").glob("*.stl"))
    assert len(stl) == 2 and all(len(name) == 24 for name in stl)  # 20 hex digits + .stl
    check = json.loads((output / ".mjcfbuild" / "check.json").read_text())
    assert check["passes"], check["failures"]
    part = check["parts"]["hand_"]
    assert part["missing"] == [] and part["problems"] == []
    assert part["max_position_error"] < 1e-9 and part["max_rotation_error"] < 1e-9
    report = (output / "report" / "report.md").read_text()
    assert "MJCF part hand_ (hand/hand.xml) against the part alone" in report
    # The report lists the hand's own actuator, as the part's.
    assert "| hand_grip | hand_split | general | part |" in report


def test_editing_the_hand_reruns_its_part_and_the_assembly_only(tmp_path):
    folder = copy_example("arm_mjcf_gripper", tmp_path / "one")
    manifest = folder / "robot.yaml"
    first = mjcfbuild.build(manifest, jobs=2, check=False)
    assert {"expand", "plan", "part:hand_", "assemble"} <= set(first.ran)
    defaults = folder / "hand" / "defaults.xml"  # included by hand.xml: a dependency too
    defaults.write_text(defaults.read_text().replace('damping="2"', 'damping="2.5"'))
    second = mjcfbuild.build(manifest, jobs=2, check=False)
    assert sorted(second.ran) == ["assemble", "part:hand_"]
    model = mujoco.MjModel.from_xml_path(str(second.robot))
    assert model.dof_damping[model.joint("hand_right_finger").dofadr[0]] == 2.5
    assert mjcfbuild.build(manifest, jobs=2, check=False).ran == []
    # Another folder, another cache, another hash seed: the same bytes.
    other = copy_example("arm_mjcf_gripper", tmp_path / "elsewhere" / "two")
    other_defaults = other / "hand" / "defaults.xml"
    other_defaults.write_text(defaults.read_text())
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache-2"), "PYTHONHASHSEED": "2"}
    done = run_cli("build", "-q", "--no-check", cwd=other, env=env)
    assert done.code == EXIT_OK, done.stderr
    names = ["arm_with_mjcf_hand.xml", "scene.xml"]
    _, mismatch, errors = filecmp.cmpfiles(folder / "mjcf", other / "mjcf", names, shallow=False)
    assert mismatch == [] and errors == []
    assets = sorted(p.name for p in (folder / "mjcf" / "assets").iterdir())
    _, mismatch, errors = filecmp.cmpfiles(
        folder / "mjcf" / "assets", other / "mjcf" / "assets", assets, shallow=False
    )
    assert mismatch == [] and errors == []


SECOND_PART = """    to: b_palm
    prefix: a_
  - source: {mjcf: hand/hand.xml}
    to: a_tcp
    prefix: b_"""


@pytest.mark.parametrize(
    ("where", "old", "new", "code", "message", "location"),
    [
        ("robot.yaml", "to: tool0", "to: tool9", 3, "'to' names 'tool9'", "robot.yaml:16:"),
        ("robot.yaml", "    to: tool0\n    prefix: hand_", SECOND_PART, 3, "cycle", "robot.yaml:"),
        ("hand.xml", 'body name="palm"', 'body name="arm_link"', 3, "'upper_arm_link'", None),
        ("hand.xml", 'size="0.02 0.05 0.015"', 'size="0 0 0"', 4, "size 0", "hand/hand.xml:LINE:"),
        ("hand.xml", "<tendon>", "<tendon", 4, "XML error", "hand/hand.xml:"),
        ("hand.xml", '"split">', '"split"><joint joint="x" coef="1"/>', 4, "'x'", "hand/hand.xml"),
    ],
)
def test_bad_attachments_are_one_line_errors_and_write_nothing(
    tmp_path, where, old, new, code, message, location
):
    folder = copy_example("arm_mjcf_gripper", tmp_path)
    path = folder / "robot.yaml" if where == "robot.yaml" else folder / "hand" / "hand.xml"
    assert old in path.read_text()
    line = path.read_text()[: path.read_text().index(old)].count("\n") + 1
    location = location and location.replace("LINE", str(line))
    path.write_text(path.read_text().replace(old, new))
    if "arm_link" in new:  # a part body 'arm_link' becomes the arm's 'upper_arm_link'
        manifest = folder / "robot.yaml"
        manifest.write_text(manifest.read_text().replace("prefix: hand_", "prefix: upper_"))
        location = "robot.yaml:17:"
    done = run_cli("build", cwd=folder)
    assert done.code == {3: EXIT_MANIFEST, 4: EXIT_INPUT}[code], done.stderr
    errors = [row for row in done.stderr.splitlines() if "error" in row]
    assert len(errors) == 1 and message in errors[0], done.stderr
    assert errors[0].startswith(f"mjcfbuild: error: {location}"), errors[0]
    assert not (folder / "mjcf" / "arm_with_mjcf_hand.xml").exists()
    assert "Traceback" not in done.stderr


def test_an_unnamed_joint_of_the_hand_is_named_after_its_body(tmp_path):
    """A thumb joint with no name failed the check twice over ("joint '#6' has no actuator",
    "joint 'hand_' not in the model"), and no rule or home could name it."""
    folder = copy_example("arm_mjcf_gripper", tmp_path)
    hand = folder / "hand" / "hand.xml"
    text = hand.read_text()
    thumb = (
        '<body name="thumb" pos="0.03 0 0.03"><joint type="hinge" axis="1 0 0" '
        'range="-0.5 0.5" damping="0.1"/><geom class="collision" type="capsule" '
        'size="0.005 0.01"/></body>\n'
    )
    index = text.index("</body>", text.index('<body name="palm"'))
    text = text[:index] + thumb + text[index:]
    hand.write_text(text.replace('qpos="0.02 0.02"', 'qpos="0.02 0.02 0"'))
    manifest = folder / "robot.yaml"
    text = manifest.read_text().replace("  elbow: 0.6\n", "  elbow: 0.6\n  hand_thumb_joint: 0.2\n")
    manifest.write_text(text)
    result = run_cli("build", str(manifest))
    assert result.code == EXIT_OK, result.stderr
    assert "named after their bodies ('thumb_joint', prefixed in the model)" in result.stderr
    model = mujoco.MjModel.from_xml_path(str(folder / "mjcf" / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    assert data.joint("hand_thumb_joint").qpos[0] == pytest.approx(0.2)
