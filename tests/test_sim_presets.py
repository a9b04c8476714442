"""Closed loop with every local planner preset of ``optplan.local`` on one small scenario:
a 10 m x 8 m room, three known cells, one unknown cell near the straight line to the goal
and one mover crossing the last third of the way."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op

local = pytest.importorskip("optplan.local")

ROWS = [[0] * 10 for _ in range(8)]
ROWS[1][2] = ROWS[1][3] = 1      # known cells (2, 6), (3, 6)
ROWS[6][6] = 1                   # known cell (6, 1)
SCENARIO = {"map": ROWS, "start": [0.5, 0.5, 30], "goal": [9.5, 6.5], "time_limit": 60,
            "robot": {"radius": 0.2, "v_max": 1.0, "w_max_deg": 60, "a_max": 0.5, "alpha_max_deg": 120},
            "unknown_obstacles": [{"cells": [[4, 3]]}],
            "dynamic_obstacles": [{"radius": 0.3, "waypoints": [[7.5, 1.0], [7.5, 7.0]], "speed": 0.3,
                                   "phase": 3.0}]}

# presets that did not reach this goal collision-free when this test was written (strict: a fix
# makes the test fail as XPASS, so the mark is removed with the fix)
KNOWN_FAILURES = {
    "dwa": "no global guidance (goal only, as the papers' traditional DWA): stops in front of the unknown cell",
    "follow": "blind by design (the global path driven without avoidance): runs through the unknown cell",
}


@pytest.fixture(scope="module")
def runs():
    sc = op.load_scenario(SCENARIO)
    return sc, {p: op.simulate(sc, local_planner=p, seed=0) for p in local.algorithm_names()}


@pytest.mark.parametrize("preset", local.algorithm_names())
def test_every_preset_drives_within_the_robot_limits(runs, preset):
    sc, results = runs
    res, r = results[preset], sc.robot
    T = res.trajectory
    assert np.all(np.isfinite(T)) and res.steps == len(T) - 1
    assert res.max_abs_accel <= r.a_max + 1e-9
    assert res.max_abs_ang_accel <= r.alpha_max + 1e-9
    assert np.all((T[:, 4] >= r.v_min - 1e-9) & (T[:, 4] <= r.v_max + 1e-9))
    assert np.all(np.abs(T[:, 5]) <= r.w_max + 1e-9)


@pytest.mark.parametrize("preset", [pytest.param(p, marks=pytest.mark.xfail(strict=True, reason=KNOWN_FAILURES[p]))
                                    if p in KNOWN_FAILURES else p for p in local.algorithm_names()])
def test_preset_reaches_the_goal_without_collision(runs, preset):
    res = runs[1][preset]
    assert res.reached and res.collisions == 0, res.message
    assert res.min_clearance > 0


def test_qp_dwa_keeps_acceleration_and_jerk_limits():
    spec = dict(SCENARIO, robot=dict(SCENARIO["robot"], jerk_max=2.0))
    sc = op.load_scenario(spec)
    res = op.simulate(sc, local_planner="qp-dwa", seed=0)
    assert res.reached and res.collisions == 0, res.message
    assert res.max_abs_accel <= sc.robot.a_max + 1e-6
    assert res.max_abs_ang_accel <= sc.robot.alpha_max + 1e-6
    assert res.max_abs_jerk <= sc.robot.jerk_max + 1e-6
