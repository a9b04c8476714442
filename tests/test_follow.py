"""``follow``: the global path driven blind, the baseline of "a global planner alone cannot avoid
what its map does not hold" (hou2024 §4.4-4.5)."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.local import algorithm_names, make_local_planner


def _off_path(r) -> float:
    """Largest distance (m) of the driven positions from the global path polyline."""
    P = np.asarray(r.trajectory)[:, 1:3]
    G = np.asarray(r.global_path, float)
    A, B = G[:-1], G[1:]
    d = B - A
    t = np.clip(((P[:, None] - A) * d).sum(-1) / np.maximum((d * d).sum(-1), 1e-18), 0, 1)
    return float(np.hypot(*(A + t[..., None] * d - P[:, None]).transpose(2, 0, 1)).min(axis=1).max())


def test_follow_drives_the_known_map_cleanly_and_stays_on_the_path():
    r = op.simulate("hou2024_table4_0", local_planner="follow", seed=0)
    assert r.reached and r.collisions == 0, r.message
    assert _off_path(r) < 0.1
    sc = op.load_scenario("hou2024_table4_0")
    assert r.max_abs_accel <= sc.robot.a_max * (1 + 1e-6)


def test_follow_runs_into_an_obstacle_its_map_does_not_hold():
    """One random obstacle on the path: the blind follower drives into it, missa-dwa does not."""
    blind = op.simulate("hou2024_table4_1", local_planner="follow", seed=0)
    assert blind.collisions > 0 and blind.replans == 0
    fused = op.simulate("hou2024_table4_1", local_planner="missa-dwa", seed=0)
    assert fused.reached and fused.collisions == 0


def test_follow_is_a_checked_local_planner():
    assert "follow" in algorithm_names()
    sc = op.load_scenario("hou2024_table4_0")
    with pytest.raises(op.ParameterError, match="reached"):
        make_local_planner("follow", sc.robot, sc.dt, reached=-1.0)
    with pytest.raises(op.ParameterError, match="unknown parameter"):
        make_local_planner("follow", sc.robot, sc.dt, look_ahead=1.0)
    with pytest.raises(op.ParameterError, match="no window program"):
        make_local_planner("follow", sc.robot, sc.dt, local_program="default")
