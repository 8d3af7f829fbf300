"""What a preview shows, read from MJCF files: includes put in place, unseen parts left out."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.check.drawn import drawn_model_xml


def test_bodies_nested_thousands_deep_are_walked_without_recursion(tmp_path: Path):
    depth = 3000
    body = '<body><joint damping="3" range="0 1"/><geom size="0.1"/><include file="part.xml"/>'
    (tmp_path / "model.xml").write_text(
        f"<mujoco><worldbody>{body * depth}{'</body>' * depth}</worldbody>"
        '<actuator><motor joint="j"/></actuator></mujoco>'
    )
    (tmp_path / "part.xml").write_text('<mujoco><site name="s"/><sensor><touch/></sensor></mujoco>')

    drawn = drawn_model_xml(tmp_path / "model.xml")

    assert drawn is not None
    text = drawn.decode()
    assert text.count("<body>") == depth and text.count('<site name="s" />') == depth
    assert "damping" not in text and 'range="0 1"' not in text  # joint dynamics cannot show
    assert "<actuator" not in text and "<sensor" not in text and "<include" not in text


def test_includes_nested_past_twenty_files_are_unreadable(tmp_path: Path):
    (tmp_path / "model.xml").write_text('<mujoco><include file="loop.xml"/></mujoco>')
    (tmp_path / "loop.xml").write_text('<mujoco><include file="loop.xml"/></mujoco>')
    assert drawn_model_xml(tmp_path / "model.xml") is None


def test_the_text_is_what_elementtree_writes():
    import xml.etree.ElementTree as ET

    from mjcfbuild.check.drawn import _serialised

    odd = ET.fromstring(
        '<mujoco model="a&amp;b &quot;q&quot; &#10;&#9;&#13;é"><worldbody>text &lt;&gt; ü'
        '<body name="b"><geom size="1"/>tail &amp;</body><site/></worldbody>end</mujoco>'
    )
    hand = ET.parse(Path(__file__).parents[2] / "examples/arm_mjcf_gripper/hand/hand.xml")
    for root in (odd, hand.getroot()):
        assert _serialised(root) == ET.tostring(root)
