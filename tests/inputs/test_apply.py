"""Applying inputs: merged defaults, names checked with the ones that exist listed."""

from __future__ import annotations

import pytest

import mjcfbuild
from mjcfbuild.errors import BuildFailed
from tests.conftest import two_link_urdf, write


def build(tmp_path, inputs: str):
    write(tmp_path / "robot.urdf", two_link_urdf())
    write(tmp_path / "inputs.xml", f"<mujoco_inputs>{inputs}</mujoco_inputs>")
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: robot.urdf}\nmujoco_inputs: {file: inputs.xml}\n",
    )
    return mjcfbuild.build(tmp_path / "robot.yaml")


def error(tmp_path, inputs: str) -> str:
    with pytest.raises(BuildFailed) as info:
        build(tmp_path, inputs)
    return info.value.one_line()


def test_unknown_joint_in_an_actuator_names_element_line_and_existing_joints(tmp_path):
    text = error(
        tmp_path,
        '<raw_inputs>\n<actuator>\n<motor name="m" joint="elbow"/></actuator></raw_inputs>',
    )
    assert "inputs.xml:3: <motor 'm'> joint=\"elbow\" names a joint that does not exist" in text
    assert "joint names: hinge" in text


def test_unknown_body_in_an_exclude(tmp_path):
    text = error(
        tmp_path,
        '<raw_inputs><contact>\n<exclude body1="base" body2="hand"/></contact></raw_inputs>',
    )
    assert 'inputs.xml:2: <exclude> body2="hand" names a body that does not exist' in text
    assert "body names: arm, base, world" in text


def test_unknown_modify_target_lists_what_exists(tmp_path):
    text = error(
        tmp_path,
        '<processed_inputs>\n<modify_element type="joint" name="nope" damping="1"/></processed_inputs>',
    )
    assert "modify_element: no joint named 'nope'" in text and "joint names: hinge" in text


@pytest.mark.parametrize(
    ("target", "says"),
    [
        ('type="joint" name="hinj"', "no joint named 'hinj'; did you mean 'hinge'? (joint names:"),
        ('type="body" name="amr"', "no body named 'amr'; did you mean 'arm'? (body names: arm,"),
        ('type="site" name="bse"', "no site named 'bse'; did you mean 'base'? (site names:"),
        (
            'type="camera" name="ey"',
            "no camera named 'ey'; did you mean 'eye'? (camera names: eye)",
        ),
        (
            'type="geom" mesh="amr" class="visual"',
            "no geom with mesh 'amr' and class 'visual': no mesh is named 'amr'",
        ),
        (
            'type="jiont" name="hinge"',
            "unknown element type 'jiont'; did you mean 'joint'? "
            "(element types with names in the model: body, camera, geom, joint",
        ),
    ],
)
def test_a_misspelt_modify_target_names_the_closest(tmp_path, target, says):
    """Every type of element a modification looks up by name says the closest name, and a
    misspelt type is said to be unknown, with the closest type (issue 43)."""
    text = error(
        tmp_path,
        '<processed_inputs>\n<camera site="arm" name="eye"/>\n'
        f'<modify_element {target} user="1"/></processed_inputs>',
    )
    assert "inputs.xml:3: modify_element: " in text
    assert says in text


def test_camera_at_unknown_link(tmp_path):
    text = error(tmp_path, '<processed_inputs>\n<camera site="eye" name="c"/></processed_inputs>')
    assert (
        "camera refers to link 'eye', which does not exist" in text and "links: arm, base" in text
    )


@pytest.mark.parametrize(
    ("element", "says"),
    [
        (
            '<camera site="arm" name="c" fovyy="40"/>',
            "inputs.xml:2: camera 'c' sets 'fovyy', which MuJoCo's <camera> does not have; "
            "did you mean 'fovy'? (<camera> attributes: axisangle, class, euler,",
        ),
        (
            '<modify_element type="joint" name="hinge" dampng="1"/>',
            "inputs.xml:2: modify_element joint 'hinge' sets 'dampng', which MuJoCo's <joint> "
            "does not have; did you mean 'damping'? (<joint> attributes: actuatorfrclimited,",
        ),
    ],
)
def test_a_mujoco_attribute_mujoco_lacks_is_an_error_at_its_input(tmp_path, element, says):
    """Not MuJoCo's "unrecognized attribute" about the assembled model, which names no input."""
    text = error(tmp_path, f"<processed_inputs>\n{element}</processed_inputs>")
    assert says in text, text


@pytest.mark.parametrize(
    ("raw", "says"),
    [
        (
            '<actuator>\n<position name="p" joint="hinge" kpp="30"/></actuator>',
            "inputs.xml:3: <position> has no attribute 'kpp'; did you mean 'kp'? "
            "(MuJoCo's <position> attributes: ",
        ),
        (
            '<default>\n<default class="soft">\n<geom rbga="1 0 0 1"/></default></default>',
            "inputs.xml:4: <geom> inside <default> has no attribute 'rbga'; did you mean 'rgba'?",
        ),
        (  # a nested element's own line, not its raw element's
            '<tendon>\n<fixed name="t">\n\n<joint joint="hinge" coeff="1"/>\n</fixed></tendon>',
            "inputs.xml:5: <joint> inside <fixed> has no attribute 'coeff'; did you mean 'coef'?",
        ),
        (
            '<option timestep="0.002" integrater="RK4"/>',
            "inputs.xml:2: <option> has no attribute 'integrater'; did you mean 'integrator'?",
        ),
    ],
)
def test_a_raw_attribute_mujoco_lacks_is_an_error_at_its_input(tmp_path, raw, says):
    """Not MuJoCo's "unrecognized attribute" about the assembled model, which names no input."""
    text = error(tmp_path, f"<raw_inputs>\n{raw}</raw_inputs>")
    assert says in text, text


@pytest.mark.parametrize("timestep", ["-1", "0", "nan", "inf", "fast"])
def test_a_raw_timestep_that_is_no_positive_number_is_an_error_at_its_input(tmp_path, timestep):
    """MuJoCo compiles any timestep; the build's trials and reports cannot simulate with it."""
    text = error(tmp_path, f'<raw_inputs>\n<option timestep="{timestep}"/></raw_inputs>')
    assert (
        f'inputs.xml:2: <option timestep="{timestep}">: the timestep must be a positive number '
        "of seconds (MuJoCo's default is 0.002)"
    ) in text, text


@pytest.mark.parametrize("timestep", ["1", "0.06", "1e-6"])
def test_a_raw_timestep_a_build_cannot_simulate_with_is_an_error_at_its_input(tmp_path, timestep):
    """1 s passed the check (its 1 s hold was one step, a servo swinging out of range); 1e-9
    ran for hours."""
    text = error(tmp_path, f'<raw_inputs>\n<option timestep="{timestep}"/></raw_inputs>')
    assert (
        f'inputs.xml:2: <option timestep="{timestep}">: a build simulates with timesteps from '
        "1e-05 to 0.05 s"
    ) in text, text


@pytest.mark.parametrize(
    ("option", "says"),
    [
        ('gravity="0 0 nan"', '<option gravity="0 0 nan">: every number must be finite'),
        ('impratio="inf"', '<option impratio="inf">: every number must be finite'),
        ('iterations="0"', '<option iterations="0">: with no solver iterations nothing holds'),
    ],
)
def test_a_raw_option_a_build_cannot_simulate_with_is_an_error_at_its_input(tmp_path, option, says):
    text = error(tmp_path, f"<raw_inputs>\n<option {option}/></raw_inputs>")
    assert f"inputs.xml:2: {says}" in text, text


@pytest.mark.parametrize(
    ("inputs", "says"),
    [
        (
            '<processed_inputs>\n<modify_element type="joint" name="hinge" range="3 -3"/>'
            "</processed_inputs>",
            'inputs.xml:2: <joint name="hinge" range="3 -3">: the lower bound must be below the '
            'upper one (MuJoCo would compile it as no limit at all) (write it as "-3 3")',
        ),
        (
            '<raw_inputs><default>\n<joint range="1 1"/></default></raw_inputs>',
            'inputs.xml:2: <joint range="1 1">: the lower bound must be below the upper one',
        ),
        (
            '<raw_inputs><actuator>\n<position name="p" joint="hinge" ctrlrange="2 -2"/>'
            "</actuator></raw_inputs>",
            'inputs.xml:2: <position name="p" ctrlrange="2 -2">: the lower bound must be below',
        ),
    ],
    ids=["modified-joint", "default-joint", "actuator-ctrlrange"],
)
def test_a_reversed_range_in_the_inputs_is_an_error_at_its_line(tmp_path, inputs, says):
    """MuJoCo (autolimits) compiles a reversed range as no limit: the joint turned freely and
    the check said only 'no range in the model'."""
    assert says in error(tmp_path, inputs)


def test_a_range_of_zeros_or_one_turned_off_is_no_limit_as_written(tmp_path):
    result = build(
        tmp_path,
        '<raw_inputs><default><joint range="0 0"/></default><tendon><fixed name="t" '
        'range="1 -1" limited="false"><joint joint="hinge" coef="1"/></fixed></tendon>'
        "</raw_inputs>",
    )
    assert 'range="1 -1"' in result.robot.read_text()


def test_a_raw_keyframe_gives_ctrl_for_the_finished_models_actuators(tmp_path):
    """The compiles before the actuators are added leave the key's ctrl out (MuJoCo said
    "expected length 0" to a key sized for the model a user gets)."""
    result = build(
        tmp_path, '<raw_inputs>\n<keyframe><key name="k" ctrl="0.1"/></keyframe></raw_inputs>'
    )
    import mujoco

    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.key("k").ctrl.tolist() == [0.1]


def test_a_raw_keyframe_with_ctrl_of_the_wrong_length_names_its_input(tmp_path):
    text = error(
        tmp_path, '<raw_inputs>\n<keyframe><key name="k" ctrl="0.1 0.2"/></keyframe></raw_inputs>'
    )
    assert (
        "inputs.xml:2: MuJoCo rejected the model with its inputs: keyframe 0: invalid ctrl size, "
        "expected length 1"
    ) in text, text


def test_raw_attributes_of_an_element_in_any_of_its_places_are_kept(tmp_path):
    # <joint> in an equality has joint1 and polycoef, which a body's <joint> has not.
    result = build(
        tmp_path,
        '<raw_inputs><equality><joint joint1="hinge" polycoef="0 1 0 0 0"/></equality>'
        '<default><joint damping="0.5"/></default></raw_inputs>',
    )
    text = result.robot.read_text()
    assert 'joint1="hinge"' in text and 'damping="0.5"' in text


def test_input_defaults_merge_into_mjcfbuilds_classes_and_new_classes_are_added(tmp_path):
    result = build(
        tmp_path,
        '<raw_inputs><default><default class="visual"><geom group="1"/></default>'
        '<default class="heavy"><joint damping="5"/></default></default>'
        '<sensor><jointpos name="q" joint="hinge"/></sensor></raw_inputs>',
    )
    text = result.robot.read_text()
    assert text.count('<default class="visual">') == 1
    assert '<default class="heavy">' in text
    assert any("default class 'visual' sets geom group='1'" in w for w in result.warnings)


def test_decompose_mesh_input_becomes_a_decomposition_task(tmp_path):
    from tests.conftest import copy_example

    arm = copy_example("arm", tmp_path)
    (arm / "inputs.xml").write_text(
        "<mujoco_inputs><processed_inputs>"
        '<decompose_mesh mesh_name="upper_arm" threshold="0.08"/>'
        "</processed_inputs></mujoco_inputs>"
    )
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "mujoco_inputs: {file: inputs.xml}\n")
    result = mjcfbuild.build(manifest, jobs=2)
    assert "decompose:upper_arm" in result.ran
    assert list((arm / "mjcf" / "assets").glob("upper_arm_part*.obj"))


def test_modify_geom_by_mesh_file_stem_and_class(tmp_path):
    from tests.conftest import copy_example

    arm = copy_example("arm", tmp_path)
    manifest = arm / "robot.yaml"
    manifest.write_text(
        manifest.read_text()
        + "mujoco_inputs:\n  modify:\n"
        + "    - {type: geom, mesh: upper_arm.dae, class: collision, attributes: {friction: '0.5 0.01 0.001'}}\n"
    )
    text = mjcfbuild.build(manifest).robot.read_text()
    assert 'mesh="upper_arm" friction="0.5 0.01 0.001"' in text


def test_scene_block_from_the_inputs(tmp_path):
    result = build(tmp_path, '<scene><option gravity="0 0 -1"/></scene>')
    scene = result.scene.read_text()
    assert '<include file="r.xml"/>' in scene and 'gravity="0 0 -1"' in scene


def test_inputs_mujoco_rejects_are_named_in_mujocos_words(tmp_path):
    """No compile of its own checks the inputs first: the first compile's failure is reported
    as MuJoCo's complaint about the inputs."""
    with pytest.raises(BuildFailed) as info:
        build(tmp_path, '<raw_inputs>\n<actuator/>\n<option impratio="fast"/></raw_inputs>')
    text = info.value.one_line()
    # at the raw element holding the <option> MuJoCo names
    assert "inputs.xml:3: MuJoCo rejected the model with its inputs" in text, text
    assert "impratio" in text and "check the mujoco_inputs and raw MJCF" in text, text
