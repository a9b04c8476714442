"""The cheap result of ``shortest_path`` (issue 43 item 4) against the slow one it replaces.

``make_plan_result`` hands the path check's segment verdicts to the exact clearance, and
``shortest_path`` asks it to compute ``min_clearance`` on its first read
(``defer_clearance=True``). Every field must equal what the plain computation
(``validate_path``, then ``path_metrics`` with the clearance: :func:`reference_result`) gives
for the same path, on feasible and infeasible paths, with and without a clearance.
"""
from __future__ import annotations

import copy
import dataclasses
import pickle

import numpy as np
import pytest

import optplan as op
from optplan.errors import InfeasibleQueryError, ParameterError
from optplan.results import PlanResult, defer_fields
from optplan.solvers.graph import shortest_path
from optplan.solvers.result import make_plan_result
from optplan.world import geometry
from optplan.world.geometry import segments_clearance, segments_free, validate_path, validate_path_segments
from optplan.world.metrics import path_metrics


def grid_plan_result(*args, **kwargs) -> PlanResult:
    """The result ``shortest_path`` builds."""
    return make_plan_result(*args, defer_clearance=True, **kwargs)


def reference_result(world, path, algorithm: str, runtime_s: float, *, clearance: float = 0.0,
                     message: str = "") -> PlanResult:
    """The result computed plainly: the exact check, then every metric with the world."""
    P = np.asarray(path, dtype=float).reshape(-1, 2)
    check = validate_path(world, P, clearance)
    m = path_metrics(world, P)
    msg = message if check else (message + "; " if message else "") + f"infeasible: {check.reason}"
    return PlanResult(algorithm, P, bool(check), m.length, m.turn_angle_deg, m.n_turns, m.min_clearance, runtime_s,
                      np.asarray([], float), False, None, msg, 0)


def seeded_map(seed: int) -> op.GridMap:
    rng = np.random.default_rng(seed)
    res, origin = ((1.0, (0.0, 0.0)), (0.5, (1.0, -2.0)), (0.25, (-3.5, 7.25)))[seed % 3]
    occ = rng.random((18 + seed % 5, 22 - seed % 4)) < 0.25
    return op.GridMap(occ, resolution=res, origin=origin)


def free_points(grid, rng, n: int, centred: bool) -> np.ndarray:
    iy, ix = np.nonzero(~grid.occ)
    k = rng.choice(len(ix), size=n, replace=False)
    off = np.full((n, 2), 0.5) if centred else rng.uniform(0.05, 0.95, (n, 2))
    return grid.to_world(np.stack([ix[k], iy[k]], axis=1) + off)


def same_result(a: PlanResult, b: PlanResult) -> None:
    assert type(a) is type(b) is PlanResult
    da, db = a.to_dict(), b.to_dict()
    assert da.keys() == db.keys()
    for k in da:
        assert da[k] == db[k], k
    assert np.array_equal(a.path, b.path)
    assert (a.min_clearance == b.min_clearance) or (np.isnan(a.min_clearance) and np.isnan(b.min_clearance))


QUERIES = [(seed, method, centred, clearance) for seed in range(6) for method in ("astar", "dijkstra", "visibility")
           for centred in (True, False) for clearance in (0.0, 0.1)]


@pytest.mark.parametrize("seed, method, centred, clearance", QUERIES)
def test_shortest_path_result_equals_the_slow_build(seed, method, centred, clearance):
    grid = seeded_map(seed)
    rng = np.random.default_rng(100 + seed)
    pts = free_points(grid, rng, 8, centred)
    done = 0
    for s, g in zip(pts[::2], pts[1::2]):
        try:
            r = shortest_path(grid, s, g, method=method, clearance=clearance * grid.resolution)
        except InfeasibleQueryError:
            continue
        done += 1
        c = clearance * grid.resolution
        slow = reference_result(grid, r.path, method, r.runtime_s, clearance=c, message=r.message)
        same_result(r, slow)
        assert r.feasible == bool(validate_path(grid, r.path, c))
        assert r.min_clearance == path_metrics(grid, r.path).min_clearance
    assert done or clearance > 0  # without clearance these maps leave a reachable pair


def odd_paths(grid, rng):
    """Feasible and infeasible polylines: through obstacles, off the map, along grid lines,
    through lattice vertices (diagonal meetings of blocked cells), repeated points."""
    W, H = grid.width, grid.height
    for _ in range(12):
        n = int(rng.integers(2, 7))
        kind = rng.integers(4)
        if kind == 0:    # anywhere, a little past the border too
            g = rng.uniform(-0.5, [W + 0.5, H + 0.5], (n, 2))
        elif kind == 1:  # lattice vertices
            g = rng.integers(0, [W + 1, H + 1], (n, 2)).astype(float)
        elif kind == 2:  # cell centres
            g = rng.integers(0, [W, H], (n, 2)) + 0.5
        else:            # a straight path with a repeated point
            g = rng.integers(0, [W, H], (n, 2)) + 0.5
            g[1] = g[0]
        yield grid.to_world(g)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("clearance", [0.0, 0.3])
def test_the_shared_and_deferred_result_equals_the_plain_one_on_any_path(seed, clearance):
    grid = seeded_map(seed)
    rng = np.random.default_rng(seed)
    c = clearance * grid.resolution
    verdicts = set()
    for P in odd_paths(grid, rng):
        fast = grid_plan_result(grid, P, "astar", 0.5, clearance=c, message="m")
        slow = reference_result(grid, P, "astar", 0.5, clearance=c, message="m")
        same_result(fast, slow)
        same_result(make_plan_result(grid, P, "astar", 0.5, clearance=c, message="m"), slow)
        verdicts.add(fast.feasible)
    assert False in verdicts  # the infeasible branch (crossing depths from the shared verdicts) ran
    # paths free without clearance, judged with more clearance than they keep (A* paths keep
    # half a cell): refused by the check, yet their clearance is a positive distance
    pts = free_points(grid, rng, 6, False)
    for s, g in zip(pts[::2], pts[1::2]):
        try:
            P = shortest_path(grid, s, g, method="astar").path
        except InfeasibleQueryError:
            continue
        for k in (0.6, 0.2):
            fast = grid_plan_result(grid, P, "astar", 0.5, clearance=k * grid.resolution)
            same_result(fast, reference_result(grid, P, "astar", 0.5, clearance=k * grid.resolution))
            same_result(make_plan_result(grid, P, "astar", 0.5, clearance=k * grid.resolution),
                        reference_result(grid, P, "astar", 0.5, clearance=k * grid.resolution))
            verdicts.add((k, fast.feasible, fast.min_clearance > 0))
    assert (0.6, False, True) in verdicts


def test_validate_path_segments_is_validate_path():
    grid = seeded_map(1)
    rng = np.random.default_rng(7)
    for P in list(odd_paths(grid, rng)) + [np.zeros((0, 2)), np.array([[np.nan, 1.0], [1.0, 1.0]]), "x"]:
        for c in (0.0, 0.2):
            check, seg = validate_path_segments(grid, P, c)
            ref = validate_path(grid, P, c)
            assert (check.ok, check.reason) == (ref.ok, ref.reason)
            assert np.array_equal(check.bad_segments, ref.bad_segments)
            assert np.array_equal(check.bad_points, ref.bad_points)
            if seg is not None:
                Q = np.asarray(P, float)
                assert np.array_equal(seg, segments_free(grid, Q[:-1], Q[1:], c))


def test_segments_clearance_with_given_verdicts():
    grid = seeded_map(2)
    rng = np.random.default_rng(3)
    a = grid.to_world(rng.uniform(0, [grid.width, grid.height], (40, 2)))
    b = grid.to_world(rng.uniform(0, [grid.width, grid.height], (40, 2)))
    free = segments_free(grid, a, b)
    assert not free.all() and free.any()
    assert np.array_equal(segments_clearance(grid, a, b, free=free), segments_clearance(grid, a, b))
    with pytest.raises(ParameterError, match="one verdict per segment"):
        segments_clearance(grid, a, b, free=free[:-1])


def test_clearance_reuses_the_checks_segment_pass(monkeypatch):
    """Without clearance, building the result runs the segment rule once (the check), and
    reading min_clearance does not run it again; with a clearance the metric runs its own."""
    grid = seeded_map(0)
    s, g = free_points(grid, np.random.default_rng(1), 2, True)
    calls = []
    rule = geometry.segments_free
    monkeypatch.setattr(geometry, "segments_free", lambda *a, **k: calls.append(1) or rule(*a, **k))
    P = shortest_path(grid, s, g, method="astar").path
    calls.clear()
    r = grid_plan_result(grid, P, "astar", 0.0)
    assert len(calls) == 1
    value = r.min_clearance
    assert len(calls) == 1
    assert value == path_metrics(grid, P).min_clearance
    calls.clear()
    r = grid_plan_result(grid, P, "astar", 0.0, clearance=0.01)
    r.min_clearance
    assert len(calls) == 2


def test_deferred_clearance_behaves_like_a_field():
    grid = seeded_map(4)
    s, g = free_points(grid, np.random.default_rng(2), 2, False)
    r0 = shortest_path(grid, s, g, method="astar")
    expected = path_metrics(grid, r0.path).min_clearance

    r = shortest_path(grid, s, g, method="astar")
    r.path[1:-1] += 0.37 * grid.resolution          # the path edited in place before the read
    assert r.min_clearance == expected               # the value of the path that was returned
    for make in (lambda r: pickle.loads(pickle.dumps(r)), copy.copy, copy.deepcopy,
                 lambda r: dataclasses.replace(r, seed=3)):
        fresh = shortest_path(grid, s, g, method="astar")
        other = make(fresh)
        assert other.min_clearance == expected and fresh.min_clearance == expected
        assert "_deferred" not in vars(other) or not vars(other)["_deferred"]
    fresh = shortest_path(grid, s, g, method="astar")
    assert fresh.to_dict()["min_clearance"] == expected
    assert f"min_clearance={expected!r}" in repr(shortest_path(grid, s, g, method="astar"))
    fresh = shortest_path(grid, s, g, method="astar")
    fresh.min_clearance = 9.0                        # assigning a deferred field sets it
    assert fresh.min_clearance == 9.0 and pickle.loads(pickle.dumps(fresh)).min_clearance == 9.0
    with pytest.raises(AttributeError, match="'PlanResult' object has no attribute 'nope'"):
        fresh.nope
    with pytest.raises(TypeError, match="no field"):
        defer_fields(fresh, nope=lambda: 1)
