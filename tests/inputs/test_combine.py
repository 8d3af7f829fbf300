"""Three places, one meaning: precedence robot.yaml > inputs file > URDF, with warnings."""

from __future__ import annotations

from mjcfbuild.inputs.combine import combine
from mjcfbuild.inputs.model import Inputs, RawElement
from mjcfbuild.inputs.processed import CameraInput, DecomposeInput, ModifyInput


def test_higher_precedence_wins_and_every_clash_is_warned():
    urdf = Inputs(
        raw=[
            RawElement("option", '<option timestep="0.002" integrator="Euler"/>', "r.urdf:3"),
            RawElement("actuator", '<motor name="m" joint="j"/>', "r.urdf:4"),
            RawElement("contact", '<exclude body1="a" body2="b"/>', "r.urdf:5"),
        ],
        processed=[
            CameraInput(name="cam", link="head", attributes={"fovy": "45"}).given_at("r.urdf:6"),
            DecomposeInput(mesh="hand", threshold=0.05).given_at("r.urdf:7"),
        ],
    )
    file = Inputs(
        raw=[
            RawElement("option", '<option timestep="0.001"/>', "in.xml:2"),
            RawElement("actuator", '<position name="m" joint="j"/>', "in.xml:3"),
        ],
        processed=[
            CameraInput(name="cam", link="head", attributes={"fovy": "60"}).given_at("in.xml:4")
        ],
    )
    manifest = Inputs(
        processed=[
            DecomposeInput(mesh="hand", threshold=0.02).given_at(
                "robot.yaml mujoco_inputs.decompose[0]"
            ),
            ModifyInput(type="joint", name="j", attributes={"damping": "1"}).given_at(
                "robot.yaml mujoco_inputs.modify[0]"
            ),
        ],
    )
    combined, warnings = combine([urdf, file, manifest])
    option = next(item for item in combined.raw if item.section == "option")
    assert 'timestep="0.001"' in option.xml and 'integrator="Euler"' in option.xml
    # Merged from two inputs: a child's line in the text is no line of in.xml.
    assert not option.lines_kept and option.origin == "in.xml:2"
    assert all(item.lines_kept for item in combined.raw if item.section != "option")
    actuators = [item.xml for item in combined.raw if item.section == "actuator"]
    assert actuators == ['<position name="m" joint="j"/>']
    assert len([item for item in combined.raw if item.section == "contact"]) == 1
    assert combined.of(CameraInput)[0].attributes == {"fovy": "60"}
    assert combined.of(DecomposeInput)[0].threshold == 0.02
    assert len(warnings) == 4
    assert any("option timestep given in r.urdf:3 and in.xml:2" in w for w in warnings)
    assert any(
        "camera 'cam' given in r.urdf:6 and in.xml:4; using the one in in.xml:4" in w
        for w in warnings
    )
