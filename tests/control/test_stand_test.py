"""The stand test's judgement of the recorded steps, against the step-by-step rule it replaced.

The test records each step's state and judges the whole run afterwards; a run that diverges
must still count only what the step-by-step loop counted before it stopped.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mjcfbuild.control.stand_test import _judge, _tilt, stand_test


def _step_by_step(qpos, base, start, home, addresses, heights, root):
    """The rule as one loop over the steps, stopping at the first step that is not finite."""
    height, floor = heights
    tilt = sink = roll = worst = 0.0
    worst_index = None
    for step in range(len(qpos)):
        if root:
            tilt = max(tilt, _tilt(base[step, 3]))
        sink = max(sink, height - (base[step, 2] - floor))
        roll = max(roll, float(np.linalg.norm(base[step, :2] - start)))
        if len(addresses):
            deviation = np.abs(qpos[step, addresses] - home[addresses])
            index = int(np.argmax(deviation))
            if deviation[index] > worst:
                worst, worst_index = float(deviation[index]), index
        if not np.all(np.isfinite(qpos[step])):
            tilt = math.pi
            break
    return tilt, sink, roll, worst, worst_index


@settings(max_examples=200, deadline=None)
@given(
    steps=st.integers(1, 40),
    joints=st.integers(0, 3),
    diverge_at=st.one_of(st.none(), st.integers(0, 39)),
    seed=st.integers(0, 2**16),
    root=st.sampled_from([0, 1]),
)
def test_judging_the_recorded_steps_matches_judging_each_step(
    steps, joints, diverge_at, seed, root
):
    rng = np.random.default_rng(seed)
    nq = 7 + joints
    # Few distinct values, so that ties (a deviation reached twice) happen.
    qpos = rng.integers(-3, 4, size=(steps, nq)).astype(float) / 4
    base = np.column_stack([rng.normal(size=(steps, 3)), rng.uniform(-1, 1, size=steps)])
    if diverge_at is not None and diverge_at < steps:
        qpos[diverge_at:, rng.integers(nq)] = np.nan
    home = np.zeros(nq)
    addresses = np.arange(7, nq)
    start = np.array([0.1, -0.2])
    heights = (0.5, 0.02)
    expected = _step_by_step(qpos, base, start, home, addresses, heights, root)
    judged = _judge(qpos, base, start, home, addresses, heights, root)
    # The same steps counted, the same joint named; a distance may differ in its last bit
    # (numpy 2.4 takes the norm of one row and of each row of an array by different sums).
    assert judged[:2] == expected[:2] and judged[3:] == expected[3:]
    assert judged[2] == pytest.approx(expected[2], rel=1e-15, abs=0)


def test_an_unheld_pendulum_on_a_steady_base_is_judged_by_its_joint():
    # A wide box stands; the pendulum above it (no actuator) starts 0.04 rad from upright
    # and falls within the second.
    model = mujoco.MjModel.from_xml_string(
        """<mujoco>
          <worldbody>
            <geom type="plane" size="0 0 0.05"/>
            <body pos="0 0 0.05">
              <freejoint/>
              <geom type="box" size="0.4 0.4 0.05" mass="20"/>
              <body pos="0 0 0.05">
                <joint name="top" axis="1 0 0"/>
                <geom type="capsule" fromto="0 0 0 0 0.02 0.5" size="0.01" mass="0.01"/>
                <geom type="sphere" size="0.05" pos="0 0.02 0.5" mass="1"/>
              </body>
            </body>
          </worldbody>
          <keyframe><key name="home" qpos="0 0 0.05 1 0 0 0 0"/></keyframe>
        </mujoco>"""
    )
    result = stand_test(model, 0, set(), 1.0)
    assert result.needs_controller == ""
    assert result.joint == "top"
    assert result.max_deviation > 0.5
    assert result.max_tilt < 0.2  # the base stays flat
    assert result.fails(hold_tolerance=0.1)
