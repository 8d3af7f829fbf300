"""Making a model ready: a floating robot raised onto the floor in its compiled model."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from lxml import etree

from mjcfbuild.control.apply import _move_free_bodies, _stand_on_floor

TREE = """<mujoco>
  <option integrator="implicitfast"/>
  <worldbody>
    <body name="trunk" pos="0.1 -0.2 0.05" quat="0.9 0.1 0.2 0.3">
      <freejoint name="root"/>
      <geom type="box" size="0.2 0.1 0.05" mass="4"/>
      <body name="leg" pos="0.1 0 -0.1">
        <joint name="hip" axis="0 1 0" range="-1 1"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" mass="0.5"/>
        <site name="foot" pos="0 0 -0.3"/>
      </body>
    </body>
    <body name="crate" pos="1 0 0.3"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body>
    <camera name="follow" mode="trackcom" pos="0 -2 1" xyaxes="1 0 0 0 0.5 1"/>
    <light name="spot" mode="targetbody" target="trunk" pos="0 0 3"/>
  </worldbody>
  <actuator><position joint="hip" kp="20"/></actuator>
</mujoco>"""


def _differing(moved: mujoco.MjModel, compiled: mujoco.MjModel) -> list[str]:
    names = []
    for name in dir(moved):
        value = getattr(moved, name)
        if name.startswith("_") or not isinstance(value, np.ndarray):
            continue
        if not np.array_equal(value, getattr(compiled, name), equal_nan=True):
            names.append(name)
    for name in ("meaninertia", "meanmass", "meansize"):
        if getattr(moved.stat, name) != getattr(compiled.stat, name):
            names.append(f"stat.{name}")
    return names


def test_raising_the_compiled_model_gives_the_model_compiled_again():
    root = etree.fromstring(TREE)
    model = mujoco.MjModel.from_xml_string(TREE)
    data = mujoco.MjData(model)
    lift = _stand_on_floor(root, model, data, model.qpos0.copy())
    assert lift is not None and lift > 0.1
    assert _move_free_bodies(model, data, root)
    again = mujoco.MjModel.from_xml_string(etree.tostring(root, encoding="unicode"))
    assert _differing(model, again) == []  # but the statistics MuJoCo draws with
    assert model.qpos0[2] == again.qpos0[2] == float(root.find(".//body").get("pos").split()[2])


CRATE = '<body name="crate" pos="1 0 0.3"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body>'
ENDS = "</actuator>"
FOOT_TO_ANCHOR = '<spatial springlength="-1"><site site="foot"/><site site="anchor"/></spatial>'


@pytest.mark.parametrize(
    "replacements",
    [
        [('<body name="crate"', "<body")],  # nothing to find the body by
        [(CRATE, f'<frame pos="0 0 0.4">{CRATE}</frame>')],
        [(ENDS, ENDS + '<keyframe><key name="k" qvel="0 0 1 0 0 0 0 0 0 0 0 0 0"/></keyframe>')],
        [
            ("<worldbody>", '<worldbody><site name="anchor" pos="0 0 2"/>'),
            (ENDS, ENDS + f"<tendon>{FOOT_TO_ANCHOR}</tendon>"),
        ],
        [(ENDS, ENDS + '<equality><weld body1="trunk"/></equality>')],
    ],
    ids=["unnamed", "in a frame", "keyframe", "tendon", "weld"],
)
def test_what_a_compile_could_give_otherwise_is_left_to_one(replacements):
    """Where compiling again could give more than the moved bodies (a frame moves the body, a
    keyframe without qpos, a tendon's spring length and a weld take the reference pose), the
    model is left untouched and the caller compiles."""
    tree = TREE
    for old, new in replacements:
        assert old in tree
        tree = tree.replace(old, new, 1)
    root = etree.fromstring(tree)
    model = mujoco.MjModel.from_xml_string(tree)
    before = model.qpos0.copy()
    _stand_on_floor(root, model, mujoco.MjData(model), model.qpos0.copy())
    assert not _move_free_bodies(model, mujoco.MjData(model), root)
    assert np.array_equal(model.qpos0, before)  # untouched: the caller compiles instead
