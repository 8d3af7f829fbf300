"""The check's typed results: check.json's bytes written and read back, and the words about a
robot that cannot stand without a controller, which the report, console and warnings share."""

from __future__ import annotations

import json

from mjcfbuild.check.model_check import check_model
from mjcfbuild.check.reference import read_kinematics
from mjcfbuild.check.results import (
    CheckResults,
    FastestJoint,
    FloorGap,
    Hold,
    PlausibilityResults,
    Simulation,
    Speeds,
    Stand,
)
from mjcfbuild.check.speeds import JointSpeed
from mjcfbuild.urdf.parse import parse_urdf
from tests.check.test_check_command import MJCF, ROUNDED_MJCF, ROUNDED_URDF, URDF
from tests.conftest import write


def _checked(tmp_path, urdf: str, mjcf: str) -> CheckResults:
    """The real check of a hand-written model against its URDF."""
    model = write(tmp_path / "model.xml", mjcf)
    robot = parse_urdf(urdf.encode(), "robot.urdf")
    return check_model(robot, model, model, set(), reference=read_kinematics(urdf.encode()))


def test_a_real_checks_results_read_back_to_the_same_bytes(tmp_path):
    results = _checked(tmp_path, URDF, MJCF)
    written = results.to_json()
    assert CheckResults.from_json(written) == results
    assert CheckResults.from_json(written).to_json() == written
    data = json.loads(written)
    assert data["passes"] is True and data["failures"] == []
    # Keys as check.json always had them: the speed bound is two; no home, so no hold or stand.
    assert {"max_joint_speed", "speed_bound", "menagerie_test", "meshes"} <= set(data)
    assert data["home"] is False and not {"hold", "stand", "floor_gap", "speeds"} & set(data)
    assert written == (json.dumps(data, indent=1, sort_keys=True) + "\n").encode()


def test_a_failing_check_says_so_in_its_results(tmp_path):
    text = ROUNDED_MJCF.replace("TOOL", "").replace(
        '<body name="lower" pos="0 0 -0.2">', '<body name="lower" pos="0 0 -0.3">'
    )
    results = _checked(tmp_path, ROUNDED_URDF, text)
    assert not results.passes
    assert json.loads(results.to_json())["passes"] is False
    assert CheckResults.from_json(results.to_json()).failures == results.failures


def test_a_model_that_does_not_load_has_only_that_result(tmp_path):
    results = _checked(tmp_path, URDF, "<mujoco><worldbody><body></mujoco>")
    data = json.loads(results.to_json())
    assert set(data) == {"passes", "verdict", "failures", "loads"} and data["loads"] is False
    assert data["verdict"] == "1 check(s) failed"
    assert results.console_lines() == [("loads", "FAILED: the model does not load")]


def test_keys_present_only_when_they_say_something():
    stopped = Simulation("scene.xml", 2000, False, [], stopped="mj_step: unstable")
    results = CheckResults(
        loads=True,
        simulation=stopped,
        floor=FloorGap(None),  # measured, without geometry to measure: written as null
        speeds=Speeds(None, 1.5, 50.0, []),
        stand=Stand(seconds=5.0),
    )
    data = json.loads(results.to_json())
    assert data["simulation"]["stopped"] == "mj_step: unstable"
    assert data["floor_gap"] is None and data["max_joint_speed"] is None
    assert "fell_without_controller" not in data["stand"] and "needs_controller" not in data
    assert (
        "stopped" not in json.loads(CheckResults(simulation=Simulation()).to_json())["simulation"]
    )
    assert CheckResults.from_json(results.to_json()) == results


def test_an_older_check_json_reads_with_defaults_and_a_broken_one_as_none(tmp_path):
    old = CheckResults.from_dict({"passes": True, "failures": [], "hold": {"max_deviation": 0.1}})
    assert old.hold == Hold(max_deviation=0.1)
    assert old.stand is None and old.speeds is None
    broken = write(tmp_path / "check.json", "{not json")
    assert CheckResults.read(broken) is None
    assert CheckResults.read(tmp_path / "missing.json") is None
    assert CheckResults.read(write(tmp_path / "list.json", "[]")) is None
    no_body = '{"resting_contacts": {"pairs": [{"depth": 1}]}}'
    assert CheckResults.read(write(tmp_path / "pairs.json", no_body)) is None


def test_the_standing_sentence_has_one_owner():
    fell = CheckResults(
        loads=True,
        stand=Stand(seconds=5.0, fell_without_controller="torque motors"),
        needs_controller="torque motors",
    )
    not_run = CheckResults(
        loads=True, stand=Stand(needs_controller="a_line"), needs_controller="a_line"
    )
    assert fell.standing_note() == "the robot cannot stand without a controller (torque motors)"
    assert not_run.standing_note() == (
        "the robot cannot stand without a controller (a_line): the stand test was not run"
    )
    assert not_run.standing_note(lambda text: text.replace("_", "\\_")).startswith(
        "the robot cannot stand without a controller (a\\_line)"
    )
    assert fell.warnings() == ["the robot cannot stand without a controller: torque motors"]
    assert not_run.warnings() == [
        "the robot cannot stand without a controller: a_line; the stand test was not run, and "
        "the model holds its joints, not its balance"
    ]
    assert CheckResults(loads=True).standing_note() == "" and CheckResults().warnings() == []


def test_a_passing_check_with_warnings_says_so_on_the_console_and_under_a_build(tmp_path):
    """The report's verdict counts warnings ("checks pass with 1 warning"): the console's and
    the build's must not say "check passed" / "all checks pass" beside it."""
    from mjcfbuild.cli.build import check_line

    warned = CheckResults(
        loads=True,
        plausibility=PlausibilityResults(bodies=3, warnings=["body 'a': a wrong origin"]),
    )
    assert warned.passes
    assert warned.console_verdict() == "checks pass with 1 warning: body 'a': a wrong origin"
    assert dict(warned.console_lines())["plausibility"] == "0 failures, 1 warning"
    results = write(tmp_path / "check.json", warned.to_json().decode())
    assert check_line(results, 1) == (
        "  check: checks pass with the 1 warning above (each check: `mjcfbuild check`)"
    )
    # Clean checks under a build that warned of something else (a URDF effort of 0)
    clean = write(tmp_path / "clean.json", CheckResults(loads=True).to_json().decode())
    assert check_line(clean, 2).startswith("  check: checks pass with the 2 warnings above")
    assert check_line(clean, 0).startswith("  check: all checks pass")


def test_a_floating_robots_hold_row_says_the_stand_test_judges_it():
    floating = CheckResults(loads=True, hold=Hold(3.43, "knee", floating=True))
    row = dict(floating.console_lines())["hold home 1 s"]
    assert row == "largest deviation 3.43 (knee), judged by the stand test below"
    fixed = CheckResults(loads=True, hold=Hold(0.01, "elbow"))
    assert dict(fixed.console_lines())["hold home 1 s"] == "largest deviation 0.01 (elbow)"
    # A biped on point feet: the stand test does not run, so nothing judges the hold row.
    unstood = CheckResults(
        loads=True,
        hold=Hold(3.43, "knee", floating=True),
        stand=Stand(needs_controller="its feet touch the floor at points"),
    )
    row = dict(unstood.console_lines())["hold home 1 s"]
    assert row == "largest deviation 3.43 (knee), not judged: the stand test below was not run"


def test_the_stand_verdict_in_a_word():
    stands = CheckResults(stand=Stand(seconds=5.0))
    assert stands.stand_verdict() == "stands"
    falls = CheckResults(stand=Stand(), failures=["the robot does not stand at home: it fell"])
    assert falls.stand_verdict() == "falls"
    assert CheckResults(stand=Stand(needs_controller="x")).stand_verdict() == "needs a controller"
    fell = Stand(seconds=5.0, fell_without_controller="torque motors")
    assert CheckResults(stand=fell).stand_verdict() == "needs a controller"
    assert CheckResults().stand_verdict() is None


def test_the_fastest_joint_is_on_the_console():
    results = CheckResults(loads=True, speeds=Speeds(FastestJoint("knee", 3.14159, 2.0)))
    line = ("joint speeds", "fastest knee 3.14 (limit 2), within the bound")
    assert line in results.console_lines()
    over = JointSpeed("knee", 3.14159, 2.0, "urdf", 1.5)
    results = CheckResults(
        loads=True, speeds=Speeds(FastestJoint("knee", 3.14159, 2.0), over_limit=[over])
    )
    line = (
        "joint speeds",
        "FAILED: fastest knee 3.14 (limit 2); 1 past the bound (knee at 1.57 times its limit)",
    )
    assert line in results.console_lines()
    # Faster than its limit but within its bound (50 times, a servo without a speed line):
    # listed, not failed, and the verdict agrees (TIAGo's fingers).
    finger = JointSpeed("finger", 2.4, 2.0, "urdf", 50.0)
    results = CheckResults(
        loads=True, speeds=Speeds(FastestJoint("knee", 3.14159, 4.0), over_limit=[finger])
    )
    line = (
        "joint speeds",
        "fastest knee 3.14 (limit 4); 1 joint faster than its limit, within the bound "
        "(finger at 1.2 times its limit)",
    )
    assert line in results.console_lines() and results.passes
    # A hair past its limit: shown with the digits that say so ("3.14 (limit 3.14159)" and
    # "at 1 times its limit" read as not faster at all).
    wrist = JointSpeed("wrist", 3.14161, 3.14159, "urdf", 50.0)
    results = CheckResults(
        loads=True, speeds=Speeds(FastestJoint("wrist", 3.14161, 3.14159), over_limit=[wrist])
    )
    line = (
        "joint speeds",
        "fastest wrist 3.142 (limit 3.14159); 1 joint faster than its limit, within the "
        "bound (wrist at 1.00001 times its limit)",
    )
    assert line in results.console_lines()


def test_the_reports_table_has_every_check_the_console_shows():
    """The console showed joint speeds, resting contacts and plausibility; report.md's table
    of checks left them out."""
    results = CheckResults(
        loads=True,
        speeds=Speeds(FastestJoint("knee", 3.14159, 2.0)),
        plausibility=PlausibilityResults(bodies=3, warnings=["body 'a': a wrong origin"]),
    )
    table = "\n".join(results.table_rows())
    assert "| joint speeds | fastest knee 3.14 (limit 2), within the bound |" in table
    assert "| plausibility | 0 failures, 1 warning |" in table


def test_masses_from_geometry_are_said_and_absent_from_check_json_without_them():
    """The masses line says what of the model's mass the build gave from geometry (the URDF's
    total stays the URDF's); without such masses check.json has the bytes it always had."""
    from mjcfbuild.check.results import CheckResults, Masses

    plain = Masses(urdf_total=2.0, model_total=2.0)
    assert set(plain.to_dict()) == {
        "urdf_total",
        "model_total",
        "problems",
        "repaired_bodies",
        "placeholder_bodies",
    }
    weighed = Masses(
        urdf_total=1.0,
        model_total=6.0,
        from_geometry=["arm"],
        geometry_total=5.0,
        geometry_density=1000.0,
    )
    results = CheckResults(loads=True, masses=weighed)
    assert dict(results.console_lines())["masses"] == (
        "6 kg (URDF 1 kg; 5 kg of it from the geometry of 1 link without a mass in the URDF, "
        "at 1000 kg/m^3: inertia.missing: geometry), 0 problems"
    )
    assert CheckResults.from_json(results.to_json()).masses == weighed
    assert any(
        "total 1 kg in the URDF, 6 kg in the model (5 kg of it" in row
        for row in results.table_rows()
    )
