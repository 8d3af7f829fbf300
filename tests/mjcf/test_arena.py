"""The arena is sized for a model's contacts only where MuJoCo's default would not hold them:
a long chain gets ``<size memory>``, every other model's bytes stay as they were."""

from __future__ import annotations

import mujoco
from lxml import etree

from mjcfbuild.mjcf.arena import arena_bytes, holds_contacts, size_arena


def chain(links: int, size: str = "") -> etree._Element:
    """A chain of ``links`` boxes joined by hinges about z, lying along x (as the snake of
    bench/deep_chain.py)."""
    body = ""
    for _ in range(links):
        body = (
            '<body pos="0.1 0 0"><joint type="hinge" axis="0 0 1"/>'
            f'<geom type="box" size="0.05 0.02 0.02"/>{body}</body>'
        )
    return etree.fromstring(  # huge_tree: libxml2 stops at 256 nested elements otherwise
        f'<mujoco><compiler angle="radian"/>{size}<option integrator="implicitfast"/>'
        f'<worldbody><body pos="0 0 0.02">{body}</body></worldbody></mujoco>',
        etree.XMLParser(huge_tree=True),
    )


def compiled(root: etree._Element) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(etree.tostring(root, encoding="unicode"))


def test_the_deepest_chain_gets_an_arena_for_its_contacts():
    root = chain(495)
    model = compiled(root)
    needed = arena_bytes(model)
    # 4 contacts for each of 495 boxes, 4 rows each, 495 dofs: far past the default guess.
    assert needed == 4 * 495 * 4 * 495 * 26 * 2 and needed > model.narena
    assert size_arena(root, model) == f"{-(-needed // (1 << 20))}M"
    assert [child.tag for child in root][:3] == ["compiler", "option", "size"]
    assert compiled(root).narena >= needed


def test_a_chain_the_default_holds_keeps_its_bytes():
    # 150 links used 8.3 MB of the 21 MB MuJoCo gave them under pseudorandom control.
    root = chain(150)
    before = etree.tostring(root)
    assert size_arena(root, compiled(root)) is None
    assert etree.tostring(root) == before


def test_a_memory_the_user_gave_is_left_alone():
    root = chain(495, '<size memory="1G"/>')
    assert size_arena(root, compiled(root)) is None
    assert root.find("size").get("memory") == "1G"


def test_nothing_colliding_needs_nothing():
    root = etree.fromstring(
        '<mujoco><worldbody><body><joint/><geom size="0.1" contype="0" conaffinity="0"/>'
        "</body></worldbody></mujoco>"
    )
    assert arena_bytes(compiled(root)) == 0


def test_geoms_that_only_draw_never_shrink_the_arena_mujoco_gives():
    # The assembly sizes the arena from its last trial model, which leaves out the geoms that
    # only draw, when that model holds its contacts: the published model, with every geom,
    # must then get at least that arena and need no more.
    for links in (1, 20, 150, 300):
        root = chain(links)
        trial = compiled(root)
        for body in root.iter("body"):
            for _ in range(3):
                etree.SubElement(
                    body,
                    "geom",
                    {
                        "type": "sphere",
                        "size": "0.01",
                        "contype": "0",
                        "conaffinity": "0",
                        "group": "2",
                        "density": "0",
                    },
                )
        published = compiled(root)
        assert published.narena >= trial.narena
        assert arena_bytes(published) == arena_bytes(trial)
        if holds_contacts(trial):
            assert holds_contacts(published)
