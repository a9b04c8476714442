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


def test_a_repeated_start_is_not_a_turn():
    # a via point snapped onto the start repeats it; the first real heading is not a turn
    # from "heading 0" (it counted 45 degrees here before)
    p = np.array([[0, 0], [0, 0], [1, 1], [2, 1]], float)
    assert total_turn_deg(p) == pytest.approx(45.0) and n_turns(p) == 1
    batch = np.array([[[0, 0], [0, 0], [0, 0], [1, 1]], [[0, 0], [1, 0], [2, 0], [2, 1]]], float)
    np.testing.assert_allclose(total_turn_deg(batch), [0.0, 90.0])


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


def test_min_clearance_is_exact_where_samples_miss_the_nearest_point():
    # a diagonal segment passing 0.1 m from the corner (6, 5) of the blocked cell [5,6]x[5,6];
    # samples along it never land on the foot of the perpendicular
    occ = np.zeros((10, 10), bool)
    occ[5, 5] = True
    g = op.GridMap(occ)
    u, n = np.array([1.0, 1.0]) / np.sqrt(2), np.array([1.0, -1.0]) / np.sqrt(2)
    foot = np.array([6.0, 5.0]) + 0.1 * n
    path = [foot - 4.0 * u, foot + 3.013 * u]
    assert path_metrics(g, path).min_clearance == pytest.approx(0.1, abs=1e-12)


def test_min_clearance_is_exact_on_circle_worlds_and_negative_through_obstacles():
    w = op.CircleWorld((0, 0, 10, 10), [(5.0, 5.0, 1.0)], safety=0.25)
    assert path_metrics(w, [[0.5, 6.6], [9.5, 6.6]]).min_clearance == pytest.approx(0.35, abs=1e-12)
    assert path_metrics(w, [[0.5, 5.0], [9.5, 5.0]]).min_clearance == pytest.approx(-1.25, abs=1e-12)
    g = op.GridMap.from_rows([[0, 0, 0], [0, 1, 0], [0, 0, 0]])
    assert path_metrics(g, [[0.5, 1.5], [2.5, 1.5]]).min_clearance < 0


def test_exact_min_clearance_never_exceeds_dense_samples():
    rng = np.random.default_rng(2)
    for _ in range(30):
        g = op.GridMap(rng.random((9, 11)) < 0.2, resolution=0.5)
        a, b = rng.uniform(0, [5.5, 4.5], (2, 2))
        if not g.segments_free(a, b):
            continue
        exact = g.segments_clearance(a[None], b[None])[0]
        sampled = g.clearance(a + np.linspace(0, 1, 2001)[:, None] * (b - a)).min()
        assert exact <= sampled + 1e-12 and exact >= sampled - 1e-3
