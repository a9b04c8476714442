from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.world import key_points, path_metrics, prune_direct, remove_collinear, spline_resample
from optplan.world.metrics import max_curvature, n_turns, path_length, total_turn_deg


def test_metrics_of_a_known_path():
    p = np.array([[0, 0], [1, 0], [2, 0], [2, 1], [3, 2]], float)
    assert path_length(p) == pytest.approx(3 + np.sqrt(2))
    assert total_turn_deg(p) == pytest.approx(90 + 45)
    assert n_turns(p) == 2
    # the sharpest triple is the right angle (1,0), (2,0), (2,1): circumradius sqrt(2)/2
    assert max_curvature(p) == pytest.approx(np.sqrt(2))
    assert max_curvature(p[2:]) == pytest.approx(2 * 1.0 / (1 * np.sqrt(2) * np.sqrt(5)))
    batch = np.stack([p, p[::-1]])
    np.testing.assert_allclose(path_length(batch), [3 + np.sqrt(2)] * 2)


def test_repeated_points_are_not_turns():
    p = np.array([[0, 0], [1, 0], [1, 0], [2, 0]], float)
    assert total_turn_deg(p) == 0 and n_turns(p) == 0 and max_curvature(p) == 0


def test_min_clearance_on_grid():
    g = op.GridMap.from_rows([[0, 0, 0], [0, 1, 0], [0, 0, 0]])
    m = path_metrics(g, [[0.5, 0.5], [2.5, 0.5]])
    assert m.min_clearance == pytest.approx(0.5)


def test_collinear_removal_keeps_turning_points_only():
    p = np.array([[0, 0], [1, 1], [2, 2], [3, 2], [4, 2], [4, 3]], float)
    np.testing.assert_array_equal(remove_collinear(p), [[0, 0], [2, 2], [4, 2], [4, 3]])
    # a point that reverses direction is a turn, not redundant
    q = np.array([[0, 0], [2, 0], [1, 0]], float)
    assert len(remove_collinear(q)) == 3


def test_key_points_and_direct_pruning_shorten_and_stay_valid():
    g = op.load_map("multialgo20_template")
    res = op.shortest_path(g, (0.5, 0.5), (19.5, 19.5), method="astar")
    for fn in (key_points, prune_direct):
        q = fn(g, res.path)
        assert op.validate_path(g, q)
        assert path_length(q) <= res.length + 1e-9
        assert len(q) < len(res.path)
        np.testing.assert_array_equal(q[0], res.path[0])
        np.testing.assert_array_equal(q[-1], res.path[-1])


def test_spline_passes_through_waypoints():
    w = np.array([[0, 0], [2, 3], [5, 4], [10, 10]], float)
    s = spline_resample(w, 301)
    assert s.shape == (301, 2)
    for pt in w:
        assert np.min(np.hypot(*(s - pt).T)) < 1e-9
    with pytest.raises(op.ParameterError):
        spline_resample(w, 1)
