"""Exact shortest paths among circles (the optimum for circle worlds)."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import optplan as op
from optplan.solvers.tangent_graph import plan_tangent, tangent_shortest_path
from optplan.world.metrics import path_length


def test_single_disc_matches_closed_form():
    w = op.CircleWorld((0, 0, 10, 10), [(5, 5, 1.5)], safety=0.5)
    r = plan_tangent(w, (0, 5), (10, 5))
    d, R = 5.0, 2.0
    expected = 2 * np.sqrt(d * d - R * R) + R * (np.pi - 2 * np.arccos(R / d))
    assert r.length == pytest.approx(expected, abs=1e-9)
    assert r.feasible and path_length(r.path) == pytest.approx(expected, rel=1e-4)


def test_straight_line_when_free_and_symmetric():
    w = op.CircleWorld((0, 0, 10, 10), [(5, 8, 1.0)])
    L, poly = tangent_shortest_path(w, np.array([0.0, 1.0]), np.array([10.0, 1.0]))
    assert L == pytest.approx(10.0) and len(poly) == 2


def test_never_longer_than_any_valid_polyline():
    rng = np.random.default_rng(0)
    circles = [(2.5, 2.5, 1.0), (6, 5, 1.4), (3, 7.5, 1.1), (8, 8, 0.8), (7.5, 2, 0.9)]
    w = op.CircleWorld((0, 0, 10, 10), circles, safety=0.1)
    r = plan_tangent(w, (0.2, 0.2), (9.8, 9.8))
    assert r.feasible
    rev = plan_tangent(w, (9.8, 9.8), (0.2, 0.2))
    assert rev.length == pytest.approx(r.length, abs=1e-9)
    tried = 0
    for _ in range(3000):
        mid = rng.uniform(0, 10, size=(2, 2))
        P = np.vstack([[0.2, 0.2], mid, [9.8, 9.8]])
        if op.validate_path(w, P):
            tried += 1
            assert path_length(P) >= r.length - 1e-9
    assert tried > 20


def test_shipped_circle_worlds_give_a_valid_optimum_path():
    """yang2023_env2's optimum has a very short arc whose polygon once dipped 5e-9 m into a disc."""
    from optplan.world.papermaps import paper_map

    for name in ("yang2023_env1", "yang2023_env2"):
        world, s, g = paper_map(name)
        r = plan_tangent(world, s, g)
        assert r.feasible, r.message
        assert r.length <= path_length(r.path) <= r.length * (1 + 1e-3)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 9))
def test_random_circle_worlds_give_valid_polylines(seed, n):
    rng = np.random.default_rng(seed)
    circles = np.column_stack([rng.uniform(1.5, 8.5, (n, 2)), rng.uniform(0.3, 1.5, n)])
    w = op.CircleWorld((0, 0, 10, 10), circles, safety=float(rng.uniform(0, 0.3)))
    s, g = np.array([0.05, 0.05]), np.array([9.95, 9.95])
    if not (w.is_free(s) and w.is_free(g)):
        return
    try:
        r = plan_tangent(w, s, g)
    except op.InfeasibleQueryError:
        return
    assert r.feasible, r.message
    assert path_length(r.path) >= r.length - 1e-9


def test_blocked_goal_is_reported():
    w = op.CircleWorld((0, 0, 10, 10), [(5, 5, 6.0)])
    with pytest.raises(op.InfeasibleQueryError):
        plan_tangent(w, (0.1, 0.1), (9.9, 9.9))


def test_too_many_circles_is_refused_before_anything_is_built(monkeypatch):
    """The tangent graph of n circles can hold 2 n (n - 1) tangents: a world whose graph could
    exceed MAX_GRAPH_BYTES raises a ParameterError stating the bound, at once."""
    from optplan.solvers import tangent_graph as tg

    def never(*args):
        raise AssertionError("tangents generated before the size check")

    rng = np.random.default_rng(1)
    n = 5000
    w = op.CircleWorld((0, 0, 200, 200), np.column_stack([rng.uniform(5, 195, (n, 2)), np.full(n, 0.2)]))
    monkeypatch.setattr(tg, "_common_tangents", never)
    monkeypatch.setattr(tg, "_point_tangents", never)
    with pytest.raises(op.ParameterError, match=r"GiB .*at most [\d,]+ circles"):
        op.shortest_path(w, (0.1, 0.1), (199.9, 199.9), method="visibility")
    monkeypatch.undo()
    monkeypatch.setattr(tg, "MAX_GRAPH_BYTES", tg.tangent_graph_bytes(9))
    small = op.CircleWorld((0, 0, 10, 10), [(5, 5, 1.0)])
    assert op.shortest_path(small, (0, 5), (10, 5), method="visibility").feasible
    ten = op.CircleWorld((0, 0, 10, 10), np.column_stack([np.linspace(1, 9, 10), np.full(10, 5.0), np.full(10, 0.3)]))
    with pytest.raises(op.ParameterError, match="at most 9 circles"):
        op.shortest_path(ten, (0, 0), (10, 10), method="visibility")


def test_blockwise_checks_give_the_same_optimum(monkeypatch):
    """Tiny blocks (many chunks of pairs and of segment-circle distances) change nothing."""
    from optplan.solvers import tangent_graph as tg

    rng = np.random.default_rng(3)
    circles = np.column_stack([rng.uniform(1, 19, (40, 2)), rng.uniform(0.2, 0.8, 40)])
    w = op.CircleWorld((0, 0, 20, 20), circles, safety=0.05)
    s, g = np.array([0.05, 0.05]), np.array([19.95, 19.95])
    L, _ = tg.tangent_shortest_path(w, s, g)
    monkeypatch.setattr(tg, "PAIR_CHUNK", 7)
    monkeypatch.setattr(tg, "PAIR_BLOCK", 50)
    monkeypatch.setattr(tg, "PREFILTER_T", ())
    L2, poly = tg.tangent_shortest_path(w, s, g)
    assert L2 == pytest.approx(L, abs=1e-12) and op.validate_path(w, poly)


def _random_circles(n, seed):
    import math

    rng = np.random.default_rng(seed)
    side = 10.0 * math.sqrt(n / 25)
    c = np.column_stack([rng.uniform(0, side, (n, 2)), rng.uniform(0.1, 0.4, n)])
    c = c[np.hypot(c[:, 0], c[:, 1]) > c[:, 2] + 0.5]
    c = c[np.hypot(c[:, 0] - side, c[:, 1] - side) > c[:, 2] + 0.5]
    return op.CircleWorld((0, 0, side, side), c), side


def test_bounded_tangent_graph_gives_the_full_graphs_optimum(monkeypatch):
    from optplan.solvers import tangent_graph as tg

    cases = []
    for seed in range(3):
        w, side = _random_circles(60, 90 + seed)
        cases += [(w, (0.2, 0.2), (side - 0.2, side - 0.2)), (w, (0.2, side / 2), (side - 0.2, side / 3))]
    # a wall with one gap far off the straight line: only the last, unbounded pass finds the way
    wall = [(5.0, y, 0.5) for y in np.arange(0.0, 9.01, 0.9)]
    cases.append((op.CircleWorld((0, 0, 10, 10), wall), (1.0, 1.0), (9.0, 1.0)))
    bounded = [tg.tangent_shortest_path(w, s, g)[0] for w, s, g in cases]
    monkeypatch.setattr(tg, "BOUND_SLACKS", ())
    full = [tg.tangent_shortest_path(w, s, g)[0] for w, s, g in cases]
    np.testing.assert_allclose(bounded, full, rtol=1e-12)
    assert full[-1] > 1.6 * 8.0    # the detour exceeds every finite slack
