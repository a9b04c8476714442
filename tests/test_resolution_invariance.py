"""Exact geometry in cell units: the same answers at every resolution and origin (issue 48).

A map planned at resolution 1 and origin (0, 0) and the same occupancy at 0.05 m (ROS
map_server's default), 0.1 m and 0.37 m with shifted origins must agree on every query:
reachable or not, the path's validity, and the length divided by the resolution. End
points are drawn inside cells, on cell edges and on cell corners (where floating rounding
of ``(p - origin) / resolution`` used to put a point in the wrong cell).
"""
from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

import optplan as op
from optplan.errors import InfeasibleQueryError
from optplan.worldgen.maps import generate_map

RESOLUTIONS = ((0.05, (-10.0, -10.0)), (0.1, (3.3, -2.7)), (0.37, (-0.123, 5.55)), (0.05, (512345.6, 4987654.3)))


def _endpoint(rng, occ, kind):
    iy, ix = np.argwhere(~occ)[rng.integers(int((~occ).sum()))]
    p = np.array([ix, iy], float)
    if kind == "interior":
        return p + rng.uniform(0.05, 0.95, 2)
    if kind == "edge":
        t = rng.uniform(0.05, 0.95)
        return p + [(t, 0.0), (t, 1.0), (0.0, t), (1.0, t)][rng.integers(4)]
    return p + rng.integers(0, 2, 2)


def _answer(grid, s, g, method):
    try:
        r = op.shortest_path(grid, grid.to_world(s), grid.to_world(g), method=method)
    except InfeasibleQueryError:
        return None
    return r.length / grid.resolution, bool(op.validate_path(grid, r.path))


@pytest.mark.parametrize("kind,seed", [("rooms", 5), ("maze", 6), ("random", 7), ("city", 8)])
def test_answers_do_not_depend_on_resolution_or_origin(kind, seed):
    base = generate_map(kind, 24, seed)
    rng = np.random.default_rng(seed)
    for _ in range(6):
        ks, kg = rng.choice(["interior", "edge", "corner"], 2)
        s, g = _endpoint(rng, base.occ, ks), _endpoint(rng, base.occ, kg)
        for method in ("astar", "visibility"):
            ref = _answer(base, s, g, method)
            for res, origin in RESOLUTIONS:
                got = _answer(op.GridMap(base.occ, res, origin), s, g, method)
                assert (got is None) == (ref is None), (method, res, origin, s, g)
                if ref is not None:
                    assert got[1] == ref[1] is True
                    # 1e-9 relative; with a UTM-sized origin the end points themselves are only
                    # known to ~1e-8 cells in metres (float64), so the length is too
                    tol = 4 * op.GridMap(base.occ, res, origin).snap_tolerance
                    assert got[0] == pytest.approx(ref[0], rel=1e-9, abs=tol), (method, res, origin, s, g)


def test_a_corner_given_in_metres_is_the_lattice_point_at_any_resolution():
    occ = np.zeros((6, 6), bool)
    occ[2, 2] = True
    for res, origin in RESOLUTIONS:
        grid = op.GridMap(occ, res, origin)
        corner = np.array(origin) + np.array([3, 3]) * res    # rounding puts it a hair off the lattice
        assert grid.to_grid(corner).tolist() == [3.0, 3.0]
        assert grid.point_to_grid(*corner) == (3.0, 3.0)
        # along the top edge of the blocked cell: free; 1e-6 cells into it: blocked
        a = np.array(origin) + np.array([1.5, 3.0]) * res
        b = np.array(origin) + np.array([3.5, 3.0]) * res
        assert bool(grid.segments_free(a, b))
        assert not bool(grid.segments_free(a - [0, 1e-6 * res], b - [0, 1e-6 * res]))


def test_an_inner_vertex_on_a_diagonal_meeting_is_refused_like_the_straight_segment():
    occ = np.zeros((4, 4), bool)
    occ[1, 1] = occ[2, 2] = True       # two blocked cells meet only at the point (2, 2)
    grid = op.GridMap(occ, 0.05, (-1.0, 2.0))
    a, v, b = (grid.to_world(np.array(p, float)) for p in ((1.0, 3.0), (2.0, 2.0), (3.0, 1.0)))
    straight = op.validate_path(grid, np.stack([a, b]))
    joined = op.validate_path(grid, np.stack([a, v, b]))
    assert not straight and not joined
    assert "diagonally" in joined.reason
    # the point itself may be an end point (start or goal)
    assert op.validate_path(grid, np.stack([v, a]))


def test_gridmap_copies_the_callers_array_and_leaves_it_writable():
    a = np.zeros((5, 5), bool)
    grid = op.GridMap(a)
    a[0, 0] = True
    assert a.flags.writeable and not grid.occ[0, 0] and not grid.occ.flags.writeable


def test_astar_on_a_big_empty_map_needs_memory_of_the_path_not_of_the_area():
    """Corner to corner on 1500 x 1500 (2.25 M cells): the move table is one byte a cell and
    the exact clearance of the 1500-vertex path is computed piece by piece (it took ~50 GB)."""
    n = 1500
    grid = op.GridMap(np.zeros((n, n), bool))
    tracemalloc.start()
    try:
        res = op.plan(grid, (0.5, 0.5), (n - 0.5, n - 0.5), algorithm="astar")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert res.feasible and res.length == pytest.approx((n - 1) * np.sqrt(2))
    assert res.min_clearance == pytest.approx(0.5)
    assert peak < 400e6, f"{peak / 1e6:.0f} MB"


def test_segment_clearance_pieces_agree_with_brute_force():
    rng = np.random.default_rng(3)
    occ = rng.random((30, 30)) < 0.08
    grid = op.GridMap(occ, 0.1, (2.0, -1.0))
    A = grid.to_world(rng.uniform(0, 30, (300, 2)))
    B = grid.to_world(rng.uniform(0, 30, (300, 2)))
    free = grid.segments_free(A, B)
    got = grid.segments_clearance(A[free], B[free])
    # brute force: the segment densely sampled (1/400 cell), each sample's exact point clearance
    t = np.linspace(0, 1, 8001)
    for a, b, c in zip(A[free][:40], B[free][:40], got[:40]):
        pts = a + t[:, None] * (b - a)
        assert c <= grid.clearance(pts).min() + 1e-12
        assert c >= grid.clearance(pts).min() - 0.1 * np.hypot(*(b - a)) / 8000 - 1e-12
