"""The tuning report: a pendulum's step response measured here, independently, agrees with the
report; the report is the same bytes in another folder; a gain change reruns only what it
affects."""

from __future__ import annotations

import json

import mujoco
import numpy as np
import pytest

import mjcfbuild
from tests.conftest import two_link_urdf, write

RULE = (
    "actuators:\n  rules:\n    - {joints: [hinge], frequency: 4, damping_ratio: 0.4}\n"
    "home: {hinge: 0.5}\n"
)


def _build(folder, manifest_extra: str = RULE):
    write(folder / "robot.urdf", two_link_urdf())
    write(folder / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n" + manifest_extra)
    result = mjcfbuild.build(folder / "robot.yaml")
    assert not result.errors, result.errors
    return result


def _tuning(folder) -> dict:
    return json.loads((folder / "mjcf/.mjcfbuild/tuning.json").read_text())


def _first_time(times: np.ndarray, y: np.ndarray, level: float) -> float:
    above = np.flatnonzero(y >= level)[0]
    if above == 0:
        return float(times[0])
    t0, t1, y0, y1 = times[above - 1], times[above], y[above - 1], y[above]
    return float(t0 + (t1 - t0) * (level - y0) / (y1 - y0))


def _measured_step(model_path) -> tuple[float, float]:
    """Rise time (10-90 %) and overshoot of the pendulum stepped 0.1 rad down from home,
    after 0.5 s holding home, contacts off (the report's documented test)."""
    model = mujoco.MjModel.from_xml_path(str(model_path))
    model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    for _ in range(250):  # 0.5 s at 2 ms
        mujoco.mj_step(model, data)
    start = data.qpos[0]
    data.ctrl[0] -= 0.1  # home 0.5 in [-1.5, 1.5]: more room below
    trace = []
    for _ in range(750):
        mujoco.mj_step(model, data)
        trace.append(data.qpos[0])
    times = 0.002 * np.arange(0, 751)
    values = np.array([start, *trace])
    final = values[-75:].mean()
    y = (values - start) / (final - start)
    rise = _first_time(times, y, 0.9) - _first_time(times, y, 0.1)
    return rise, float(y.max() - 1)


def test_the_reports_rise_time_and_overshoot_match_a_measured_step(tmp_path):
    result = _build(tmp_path)
    assert "tuning" in result.ran
    groups = _tuning(tmp_path)["groups"]
    assert [g["label"] for g in groups] == ["actuators.rules[0]: hinge"]
    rise, overshoot = _measured_step(result.robot)
    assert 0.1 < overshoot < 0.5  # an underdamped servo: the figures mean something
    assert groups[0]["rise_time"] == pytest.approx(rise, rel=0.05)
    assert groups[0]["overshoot"] == pytest.approx(overshoot, rel=0.05)
    assert groups[0]["per_joint"][0]["step"] == -0.1
    page = (tmp_path / "mjcf/report/report.md").read_text()
    assert "## Tuning" in page and "| actuators.rules\\[0]: hinge | 1 |" in page
    assert (tmp_path / "mjcf/report/tuning/rule0.png").read_bytes().startswith(b"\x89PNG")


def test_the_report_is_the_same_bytes_in_another_folder(tmp_path):
    _build(tmp_path / "a")
    _build(tmp_path / "b")
    for name in (".mjcfbuild/tuning.json", "report/tuning/rule0.png"):
        first = (tmp_path / "a/mjcf" / name).read_bytes()
        assert first == (tmp_path / "b/mjcf" / name).read_bytes(), name


def test_a_gain_change_reruns_the_model_and_its_reports_not_the_rest(tmp_path):
    _build(tmp_path)
    again = _build(tmp_path)
    assert again.ran == []
    changed = _build(tmp_path, RULE.replace("frequency: 4", "frequency: 6"))
    assert set(changed.ran) == {"assemble", "check", "tuning"}, changed.ran
    # The default servos form a group of their own; a group that is gone loses its plot.
    _build(tmp_path, "home: {hinge: 0.5}\n")
    assert [g["group"] for g in _tuning(tmp_path)["groups"]] == ["default_position"]
    assert sorted(p.name for p in (tmp_path / "mjcf/report/tuning").iterdir()) == [
        "default_position.png"
    ]


def test_a_weak_drive_shows_as_saturation(tmp_path):
    weak = (
        "motors:\n  define:\n    weak: {rotor_inertia: 1.0e-6, ratio: 10, peak_torque: 3,"
        " no_load_speed: 2}\n"
        "actuators:\n  rules:\n    - {joints: [hinge], motor: weak}\n"
        "home: {hinge: 0.5}\n"
    )
    _build(tmp_path, weak)
    [group] = _tuning(tmp_path)["groups"]
    # The 10 Hz servo asks ~10 times the 3 N m the drive has for a 0.1 rad step, and the
    # 2 rad/s line caps it further while it moves.
    assert group["saturation"] > 0.01
    # The default servo without the URDF's own speed line (which would cap it too).
    _build(tmp_path / "strong", "home: {hinge: 0.5}\nactuators: {speed_limits: false}\n")
    [strong] = _tuning(tmp_path / "strong")["groups"]
    assert strong["saturation"] < group["saturation"] / 2
