"""A reduced run of benchmarks/independent_check.py: planners' feasible paths and closed loops'
collision-free runs re-checked by code that does not use optplan's collision routines."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from independent_check import (  # noqa: E402
    check_queries, check_scenarios, circle_path_collides, grid_path_collides,
)


def test_the_independent_checker_sees_each_kind_of_collision():
    occ = np.zeros((4, 4), bool)
    occ[1, 1] = occ[2, 2] = True          # a double corner at (2, 2)
    occ[0, 3] = occ[1, 3] = True          # two blocked cells sharing the edge x in [3, 4], y = 1
    assert grid_path_collides(occ, 1.0, (0, 0), [[0.5, 0.5], [3.5, 0.5]]).startswith("segment 0 enters")
    assert "double corner" in grid_path_collides(occ, 1.0, (0, 0), [[1.5, 2.5], [2.5, 1.5]])
    assert "between two blocked" in grid_path_collides(occ, 1.0, (0, 0), [[3.0, 1.0], [4.0, 1.0]])
    assert "outside" in grid_path_collides(occ, 1.0, (0, 0), [[0.5, 0.5], [-0.1, 0.5]])
    assert grid_path_collides(occ, 1.0, (0, 0), [[0.5, 0.5], [1.0, 1.0], [1.0, 3.5]]) == ""  # along a free edge
    assert grid_path_collides(occ, 0.5, (1.0, 1.0), [[1.25, 1.25], [2.75, 1.25]]).startswith("segment 0")
    circles = np.array([[5.0, 5.0, 1.0]])
    assert circle_path_collides((0, 0, 10, 10), circles, 0.5, [[0.5, 6.4], [9.5, 6.4]])
    assert circle_path_collides((0, 0, 10, 10), circles, 0.5, [[0.5, 6.5], [9.5, 6.5]]) == ""  # touching


def test_no_silent_collision_on_held_out_random_queries():
    out = check_queries(40, seed0=90_000)
    assert out["feasible"] >= 25
    assert out["silent_collisions"] == 0, out["examples"]
    assert out["wrong_ends"] == 0


@pytest.mark.slow
def test_no_hidden_obstacle_in_random_closed_loops():
    out = check_scenarios(10, seed0=90_000)
    assert out["reported_clean"] >= 5 and out["hidden_obstacles"] == 0, out["examples"]


def test_no_hidden_obstacle_in_two_random_closed_loops():
    out = check_scenarios(2, seed0=91_000)
    assert out["scenarios"] == 2 and out["hidden_obstacles"] == 0, out["examples"]
