"""``output.urdf`` in robot.yaml: the build writes a URDF of the model, incrementally."""

from __future__ import annotations

import pytest

from tests.conftest import run_cli

yourdfpy = pytest.importorskip("yourdfpy")


def with_urdf_output(arm, text: str = "  urdf: example_arm.urdf\n"):
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + text)


def test_build_writes_the_urdf_and_rebuilds_only_what_changed(arm):
    with_urdf_output(arm)
    first = run_cli("build", "-q", "--no-check", cwd=arm)
    assert first.code == 0, first.stderr
    urdf = arm / "mjcf" / "example_arm.urdf"
    robot = yourdfpy.URDF.load(str(urdf), load_meshes=True, build_scene_graph=True)
    assert "elbow" in robot.actuated_joint_names and "tool0" in robot.link_map
    meshes = sorted(p.name for p in (arm / "mjcf" / "example_arm_meshes").iterdir())
    assert "upper_arm.obj" in meshes and "upper_arm.mtl" in meshes

    again = run_cli("build", "--no-check", cwd=arm)
    assert "0 run" in again.stdout

    manifest = arm / "robot.yaml"
    manifest.write_text(
        manifest.read_text().replace(
            "  urdf: example_arm.urdf\n",
            "  urdf:\n    file: example_arm.urdf\n    sites: false\n"
            "    asset_prefix: package://arm_description/mjcf/example_arm_meshes/\n",
        )
    )
    changed = run_cli("build", "--no-check", cwd=arm)
    assert "export example_arm.urdf" in changed.stdout and "1 run" in changed.stdout
    text = urdf.read_text()
    assert "package://arm_description/mjcf/example_arm_meshes/upper_arm.obj" in text
    assert '<link name="tool0"/>' not in text


def test_meshes_an_export_no_longer_uses_are_removed(arm):
    with_urdf_output(arm)
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    folder = arm / "mjcf" / "example_arm_meshes"
    assert (folder / "base.obj").exists()
    xacro = arm / "urdf" / "arm.urdf.xacro"
    text = xacro.read_text()
    # the base is drawn by a cylinder instead of its mesh
    start = text.index('<mesh filename="package://arm_description/meshes/base.stl"')
    end = text.index("/>", start) + 2
    xacro.write_text(text[:start] + '<cylinder radius="0.08" length="0.1"/>' + text[end:])
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    assert not (folder / "base.obj").exists() and not (folder / "base.mtl").exists()
    assert (folder / "upper_arm.obj").exists()


def test_clean_removes_the_urdf_and_its_meshes(arm):
    with_urdf_output(arm)
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    result = run_cli("clean", cwd=arm)
    assert result.code == 0 and "example_arm.urdf" in result.stdout
    assert not (arm / "mjcf").exists()


def test_mesh_folder_may_not_be_one_the_build_uses(arm):
    with_urdf_output(arm, "  urdf:\n    file: arm.urdf\n    meshes: assets\n")
    result = run_cli("build", cwd=arm)
    assert result.code == 3
    assert "'assets' is used by the build" in result.stderr


def _limit_values(urdf, attribute: str = "velocity") -> dict[str, float]:
    from lxml import etree

    root = etree.parse(str(urdf)).getroot()
    return {
        joint.get("name"): float(joint.find("limit").get(attribute))
        for joint in root.iter("joint")
        if joint.find("limit") is not None
    }


# The arm's URDF limits (config/joint_limits.yaml, the wrist's own): what every joint gets.
ARM_VELOCITIES = {
    "shoulder_pan": 2.0,
    "shoulder_lift": 2.0,
    "elbow": 2.5,
    "wrist_roll": 3.0,
    "left_finger_joint": 0.1,
    "right_finger_joint": 0.1,
}


ARM_EFFORTS = {
    "shoulder_pan": 60.0,
    "shoulder_lift": 60.0,
    "elbow": 30.0,
    "wrist_roll": 10.0,
    "left_finger_joint": 20.0,
}


def test_default_servos_give_back_the_urdfs_speed_limits(arm):
    """Default servos are <dcmotor>s on the URDF's effort and velocity: the export reads each
    no-load speed back from the compiled model, so the URDF's limits survive the round trip."""
    with_urdf_output(arm)
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    assert "dcmotor" in (arm / "mjcf" / "example_arm.xml").read_text()
    assert _limit_values(arm / "mjcf" / "example_arm.urdf") == pytest.approx(ARM_VELOCITIES)
    efforts = _limit_values(arm / "mjcf" / "example_arm.urdf", "effort")
    # the <dcmotor>s' stall torques and saturations are the URDF's efforts
    assert {joint: efforts[joint] for joint in ARM_EFFORTS} == pytest.approx(ARM_EFFORTS)
    assert "no speed limit known" not in result.stderr


def test_speed_limits_from_a_named_motor_and_the_source_urdf(arm):
    """Without speed lines the servos are plain <position> servos, whose speed the model does
    not know: the build gives the source URDF's limits instead, a passive joint's too, and a
    catalogue motor's no-load speed where a rule names one: read back from the <dcmotor> of a
    servo, from the build's drive for a torque motor (a <motor> says nothing of speed)."""
    manifest = arm / "robot.yaml"
    manifest.write_text(
        manifest.read_text()
        .replace("actuators:\n", "actuators:\n  speed_limits: false\n")
        .replace(
            '    - {joints: ["*finger*"], frequency: 5}\n',
            '    - {joints: ["*finger*"], frequency: 5}\n'
            "    - {joints: [elbow], motor: go1_knee}\n"
            "    - {joints: [shoulder_lift], type: motor, motor: go1_hip}\n"
            "    - {joints: [shoulder_pan], type: none}\n",
        )
    )
    with_urdf_output(arm)
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    model = (arm / "mjcf" / "example_arm.xml").read_text()
    assert (
        model.count("<dcmotor") == 1 and 'joint="shoulder_pan"' not in model.split("<actuator")[1]
    )
    assert _limit_values(arm / "mjcf" / "example_arm.urdf") == pytest.approx(
        {**ARM_VELOCITIES, "elbow": 20.06, "shoulder_lift": 30.1}
    )
