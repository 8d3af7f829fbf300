"""Masses and inertias MuJoCo would refuse are repaired (and reported) or refused."""

from __future__ import annotations

import numpy as np
import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.mjcf.bodies import build_bodies
from mjcfbuild.mjcf.inertia import InertiaPolicy, validate_masses
from mjcfbuild.urdf.parse import parse_urdf

BASE_MASS = '<inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1"/></inertial>'


def robot(inertial: str):
    # The base has a mass: a robot with none anywhere is refused whole (test_no_mass_anywhere).
    return parse_urdf(
        f"""<robot name="r"><link name="base">{BASE_MASS}</link>
        <link name="arm">{inertial}</link>
        <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
          <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
        </robot>""".encode()
    )


def check(inertial: str, mode: str = "repair"):
    bodies = build_bodies(robot(inertial), fuse_static=True)
    repairs = validate_masses(bodies, InertiaPolicy(mode=mode), "r.urdf", {"arm": 3})
    return bodies[1], repairs


def test_valid_inertia_is_left_alone():
    _, repairs = check(
        '<inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
    )
    assert repairs == []


def test_missing_inertial_on_a_moving_body_gets_the_minimum():
    body, repairs = check("")
    assert body.mass.mass == InertiaPolicy().min_mass
    assert (
        min(np.linalg.eigvalsh(np.array(body.mass.inertia))) >= InertiaPolicy().min_inertia * 0.999
    )
    assert [r.problem for r in repairs] == [
        "moving body with too small a mass",
        "principal inertia too small for a moving body",
    ]
    assert "no <inertial>" in repairs[0].describe()
    assert repairs[0].describe().startswith("r.urdf:3: body 'arm': ")  # the link's line


def test_triangle_inequality_is_restored_minimally():
    body, repairs = check(
        '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
    )
    a, b, c = sorted(np.linalg.eigvalsh(np.array(body.mass.inertia)))
    assert a + b >= c
    assert c == pytest.approx(0.1)
    assert repairs[0].problem == "principal inertia breaks A + B >= C"


def test_fail_policy_names_link_and_line():
    with pytest.raises(InputError) as info:
        check("", mode="fail")
    assert info.value.location.line == 3
    assert "link 'arm'" in info.value.message


def test_negative_mass_is_always_an_error():
    with pytest.raises(InputError, match="mass must be a number >= 0"):
        check('<inertial><mass value="-1"/><inertia ixx="1" iyy="1" izz="1"/></inertial>')


@pytest.mark.parametrize("mode", ["repair", "fail"])
def test_a_flat_plate_survives_rounding_without_a_reported_repair(tmp_path, mode):
    """A + B = C exactly (a thin plate), turned so the tensor is full: the written model loads
    under either policy, and the rounding-sized nudge is not reported as a repair."""
    from tests.mjcf.helpers import build

    urdf = """<robot name="r"><link name="base"/>
      <link name="plate"><inertial><origin rpy="2.635 -0.713 -1.700"/><mass value="2"/>
        <inertia ixx="0.0035191402" iyy="0.0545998348" izz="0.0581189750"
                 ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="j" type="continuous"><parent link="base"/><child link="plate"/></joint>
    </robot>"""
    assembly, model = build(urdf, tmp_path, inertia=InertiaPolicy(mode=mode))
    assert assembly.repairs == []
    a, b, c = sorted(model.body_inertia[1])
    assert a + b >= c


def test_no_mass_anywhere_is_refused_in_one_line():
    """0.1 g placeholders on every link would simulate nothing of the robot."""
    bodies = build_bodies(
        parse_urdf(
            b"""<robot name="r"><link name="base"/><link name="arm"/>
            <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
            <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
            </robot>"""
        ),
        fuse_static=True,
    )
    with pytest.raises(InputError, match="no link of the robot has a mass"):
        validate_masses(bodies, InertiaPolicy(), "r.urdf", {})


PROP = """<?xml version="1.0"?>
<robot name="prop">
  <link name="table">
    <visual><geometry><box size="1 0.6 0.05"/></geometry></visual>
    <collision><geometry><box size="1 0.6 0.05"/></geometry></collision>
  </link>
</robot>
"""


def test_a_free_joint_on_a_robot_without_mass_names_robot_yaml_free_joint(tmp_path):
    """A static prop with no <inertial>: nothing of the description moves, the free joint
    robot.yaml asked for made its only body a moving one; that setting is the cause."""
    from mjcfbuild.errors import EXIT_INPUT
    from tests.conftest import run_cli, simple_manifest, write

    write(tmp_path / "prop.urdf", PROP)
    manifest = simple_manifest(tmp_path, "urdf: prop.urdf", "options:\n  free_joint: true\n")
    done = run_cli("build", cwd=tmp_path)
    assert done.code == EXIT_INPUT, done.stderr
    assert (
        "mjcfbuild: error: robot.yaml:5:3: options.free_joint: a free joint floats the robot, "
        "but no link of prop.urdf has a mass (<inertial>), so its floating base 'table' cannot "
        "be simulated (set free_joint: false for a robot that stays where it is, or add each "
        "link's <inertial> (mass, centre of mass, inertia) to prop.urdf, or set inertia: "
        "{missing: geometry} in robot.yaml to give each link the mass of its geometry, as "
        "MuJoCo's own URDF import does)"
    ) in done.stderr
    # As that hint says: weighed from its geometry, the prop floats (1 x 0.6 x 0.05 m: 30 kg).
    original = manifest.read_text()
    manifest.write_text(original + "inertia:\n  missing: geometry\n")
    done = run_cli("build", cwd=tmp_path)
    assert done.code == 0, done.stderr
    assert (
        "prop.urdf:3: link 'table' has no <inertial>: given 30 kg from its collision geometry "
        "at 1000 kg/m^3 (inertia.missing: geometry)"
    ) in done.stderr
    manifest.write_text(original)
    # As the hint says: fixed to the world, the prop builds (MuJoCo's import takes it so).
    manifest.write_text(manifest.read_text().replace("free_joint: true", "free_joint: false"))
    assert run_cli("build", cwd=tmp_path).code == 0
    # convert's -f is named as the command line gave it.
    done = run_cli("convert", "-u", "prop.urdf", "-f", "-s", "-o", "out/prop.xml", cwd=tmp_path)
    assert done.code == EXIT_INPUT, done.stderr
    assert "error: the command line's -f: a free joint floats the robot" in done.stderr
    assert "(leave out -f for a robot that stays where it is" in done.stderr
    assert "or build it from a robot.yaml with inertia: {missing: geometry}" in done.stderr
