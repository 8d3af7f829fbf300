"""A floating robot whose URDF efforts are all placeholders gets force ranges it can simulate
with; plausible efforts, a rule's forcerange and fixed-base robots are left as they are."""

from __future__ import annotations

import json

import mujoco
import pytest

import mjcfbuild
from mjcfbuild.control.efforts import holding_load
from tests.conftest import write
from tests.control.helpers import actuator, load, readiness

MASS = 1.0 + 0.1 + 0.1  # base, thigh, shank (kg)
HIP_REACH = 0.3  # the shank's centre, straight below the hip (m)
KNEE_REACH = 0.1


def _leg(effort: float) -> str:
    """A box with one leg hanging straight down: hip and knee turn about y."""

    def link(name: str, mass: float, geometry: str, centre: float) -> str:
        inertia = '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>'
        return (
            f'<link name="{name}"><inertial><origin xyz="0 0 {centre}"/><mass value="{mass}"/>'
            f"{inertia}</inertial><collision><origin xyz='0 0 {centre}'/><geometry>{geometry}"
            "</geometry></collision></link>"
        )

    def joint(name: str, parent: str, child: str, z: float) -> str:
        return (
            f'<joint name="{name}" type="revolute"><parent link="{parent}"/>'
            f'<child link="{child}"/><origin xyz="0 0 {z}"/><axis xyz="0 1 0"/>'
            f'<limit lower="-10" upper="10" effort="{effort}" velocity="1000"/></joint>'
        )

    rod = '<cylinder radius="0.02" length="0.2"/>'
    return (
        '<robot name="leg">'
        + link("base", 1.0, '<box size="0.2 0.2 0.1"/>', 0.0)
        + link("thigh", 0.1, rod, -0.1)
        + link("shank", 0.1, rod, -0.1)
        + joint("hip", "base", "thigh", -0.05)
        + joint("knee", "thigh", "shank", -0.2)
        + "</robot>"
    )


def _build(folder, effort: float, free_joint: bool = True, extra: str = ""):
    write(folder / "robot.urdf", _leg(effort))
    write(
        folder / "robot.yaml",
        f"name: leg\nsource: {{urdf: robot.urdf}}\noptions: {{free_joint: {free_joint}}}\n" + extra,
    )
    return mjcfbuild.build(folder / "robot.yaml", check=False)


def _forcerange(model, name: str) -> float:
    index = actuator(model, name)
    assert model.actuator_forcelimited[index]
    low, high = model.actuator_forcerange[index]
    assert low == -high
    return float(high)


def test_placeholder_efforts_become_the_load_that_holds_the_robot(tmp_path):
    result = _build(tmp_path, effort=1000)
    model = load(result)
    weight = MASS * 9.81
    assert _forcerange(model, "hip") == pytest.approx(weight * HIP_REACH, rel=1e-6)
    assert _forcerange(model, "knee") == pytest.approx(weight * KNEE_REACH, rel=1e-6)
    [warning] = [w for w in result.warnings if "placeholders" in w]
    assert "on all 2 actuated joints the effort (1000)" in warning
    assert 'actuators: {rules: [{joints: ["*"], forcerange: [-N, N]}]}' in warning
    records = {a["joint"]: a for a in readiness(tmp_path)["actuators"]}
    assert records["hip"]["placeholder_effort"] == 1000


def test_plausible_efforts_are_kept(tmp_path):
    # The knee's 50 N m is 425 times its holding load, but the hip's is only 14 times: a real
    # robot's, so neither is touched.
    result = _build(tmp_path, effort=50)
    model = load(result)
    assert _forcerange(model, "hip") == 50 and _forcerange(model, "knee") == 50
    assert not any("placeholders" in w for w in result.warnings)


def test_a_rules_forcerange_is_kept_and_the_other_joints_still_judged(tmp_path):
    rule = "actuators:\n  rules:\n    - {joints: [hip], forcerange: [-3, 3]}\n"
    model = load(_build(tmp_path, effort=1000, extra=rule))
    assert _forcerange(model, "hip") == 3
    assert _forcerange(model, "knee") == pytest.approx(MASS * 9.81 * KNEE_REACH, rel=1e-6)


def test_a_fixed_base_robot_keeps_its_efforts(tmp_path):
    model = load(_build(tmp_path, effort=1000, free_joint=False))
    assert _forcerange(model, "hip") == 1000 and _forcerange(model, "knee") == 1000


def test_the_capped_model_passes_the_menagerie_test(tmp_path):
    # The same robot with its 1000 N m fails it (it whips its legs into a MuJoCo instability);
    # the check is the build's own.
    write(tmp_path / "robot.urdf", _leg(1000))
    write(
        tmp_path / "robot.yaml",
        "name: leg\nsource: {urdf: robot.urdf}\noptions: {free_joint: true}\n",
    )
    mjcfbuild.build(tmp_path / "robot.yaml")  # raises if the check fails
    check = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())
    assert check["passes"] and check["menagerie_test"]["warnings"] == []
    report = (tmp_path / "mjcf/report/report.md").read_text()
    assert "(URDF effort 1000, a placeholder)" in report


def test_the_holding_load_of_a_slide_is_the_weight_and_of_a_ball_nothing():
    model = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody><body><freejoint/><geom size="0.1" mass="2"/>
        <body><joint name="lift" type="slide" axis="0 0 1"/><geom size="0.05" mass="1"/></body>
        <body pos="0 0 -0.5"><joint name="ball" type="ball"/><geom size="0.05" mass="1"/></body>
        </body></worldbody></mujoco>"""
    )
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    lift = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "lift")
    ball = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "ball")
    assert holding_load(model, data, lift) == pytest.approx(4 * 9.81)
    assert holding_load(model, data, ball) == 0
