"""MuJoCo's attributes per element, read from the schema MuJoCo prints."""

from __future__ import annotations

import mujoco
import pytest

from mjcfbuild.inputs.mujoco_schema import mujoco_attributes


def recognised(element: str) -> bool:
    """Whether MuJoCo's parser knows every attribute of ``element``, put in a body (a value it
    refuses, or a class that does not exist, is another error: the attribute was known)."""
    xml = (
        f"<mujoco><worldbody><body name='b'><geom size='0.1'/>{element}</body></worldbody></mujoco>"
    )
    try:
        mujoco.MjModel.from_xml_string(xml)
    except ValueError as error:
        return "unrecognized attribute" not in str(error)
    return True


def test_body_elements_have_their_own_attributes_not_those_of_their_namesakes():
    assert {"fovy", "mode", "resolution", "name", "pos"} <= mujoco_attributes("camera")
    joint = mujoco_attributes("joint")
    assert {"damping", "frictionloss", "armature", "range"} <= joint
    assert not {"joint1", "polycoef", "coef"} & joint  # an equality's and a fixed tendon's
    assert "gravcomp" in mujoco_attributes("body")
    assert {"kp", "dampratio", "ctrlrange"} <= mujoco_attributes("position")
    assert mujoco_attributes("teleporter") == frozenset()


@pytest.mark.parametrize("tag", ["camera", "joint", "site", "light"])
def test_mujoco_knows_every_attribute_the_table_gives_and_none_it_lacks(tag):
    known = mujoco_attributes(tag)
    assert len(known) > 10
    for attribute in sorted(known):
        assert recognised(f"<{tag} {attribute}='1'/>"), attribute
    for attribute in ("fovyy", "dampng", "polycoef"):
        assert attribute not in known
        assert not recognised(f"<{tag} {attribute}='1'/>"), attribute


def test_named_elements_are_what_a_modification_may_look_up():
    from mjcfbuild.inputs.mujoco_schema import mujoco_named_elements

    named = mujoco_named_elements()
    assert {"joint", "body", "geom", "site", "camera", "position", "tendon"} <= named
    assert "jiont" not in named and "option" not in named
