"""The exact segment rule, checked against an independent parametric reference."""
from __future__ import annotations

from fractions import Fraction as Fr
from math import floor

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import optplan as op
from optplan.world.geometry import segments_free

from conftest import random_grid


def blocked(occ, ix, iy):
    h, w = occ.shape
    if ix < 0 or iy < 0 or ix >= w or iy >= h:
        return True
    return bool(occ[iy, ix])


def reference_free(occ, a, b) -> bool:
    """Walk the segment in exact rational parameters: every open piece between grid-line
    crossings is tested at its midpoint, every lattice vertex crossed is tested for a
    double corner. Independent of the column sweep used by optplan."""
    h, w = occ.shape
    ax, ay, bx, by = (Fr(v) for v in (*a, *b))
    for x, y in ((ax, ay), (bx, by)):
        if not (0 <= x <= w and 0 <= y <= h):
            return False
    if (ax, ay) == (bx, by):
        return bool(op.GridMap(occ).is_free(np.array([float(ax), float(ay)])))
    ts = {Fr(0), Fr(1)}
    for p0, p1, n in ((ax, bx, w), (ay, by, h)):
        if p1 != p0:
            for k in range(0, n + 1):
                t = (k - p0) / (p1 - p0)
                if 0 < t < 1:
                    ts.add(t)
    ts = sorted(ts)
    for t0, t1 in zip(ts[:-1], ts[1:]):
        tm = (t0 + t1) / 2
        x, y = ax + tm * (bx - ax), ay + tm * (by - ay)
        on_x, on_y = x.denominator == 1, y.denominator == 1
        ix, iy = floor(x), floor(y)
        if not on_x and not on_y:
            if blocked(occ, ix, iy):
                return False
        elif on_x and not on_y:
            if blocked(occ, ix - 1, iy) and blocked(occ, ix, iy):
                return False
        elif on_y and not on_x:
            if blocked(occ, ix, iy - 1) and blocked(occ, ix, iy):
                return False
    for t in ts[1:-1]:
        x, y = ax + t * (bx - ax), ay + t * (by - ay)
        if x.denominator == 1 and y.denominator == 1:
            X, Y = int(x), int(y)
            bl, br, tl, tr = (blocked(occ, X - 1, Y - 1), blocked(occ, X, Y - 1),
                              blocked(occ, X - 1, Y), blocked(occ, X, Y))
            if (bl and tr and not br and not tl) or (br and tl and not bl and not tr):
                return False
    return True


def test_double_corner_is_never_squeezed_through():
    g = op.GridMap.from_rows([[0, 1], [1, 0]])
    a = np.array([[0.5, 1.5], [0.0, 1.0], [1.0, 0.0], [0.25, 1.75]])
    b = np.array([[1.5, 0.5], [2.0, 1.0], [1.0, 2.0], [1.75, 0.25]])
    assert not segments_free(g, a, b).any()


def test_edges_between_free_and_blocked_are_allowed_but_not_between_two_blocked():
    g = op.GridMap.from_rows([[0, 0, 0], [1, 1, 0], [0, 0, 0]])
    # along the top edge of the blocked pair (free above): allowed
    assert segments_free(g, [0.0, 2.0], [3.0, 2.0])
    # along the edge shared by the two blocked cells (x = 1, y in [1, 2]): not allowed
    assert not segments_free(g, [1.0, 1.0], [1.0, 2.0])
    # map border counts as blocked: along the outer edge of a free row is fine
    assert segments_free(g, [0.0, 0.0], [3.0, 0.0])
    # leaving the map is not
    assert not segments_free(g, [0.5, 0.5], [3.5, 0.5])


@pytest.mark.parametrize("density", [0.15, 0.35])
def test_half_integer_segments_match_reference(density):
    rng = np.random.default_rng(7)
    for trial in range(40):
        g = random_grid(rng, 7, 9, density)
        A = rng.integers(0, 2 * 9 + 1, size=(60, 2)) / 2.0
        B = rng.integers(0, 2 * 9 + 1, size=(60, 2)) / 2.0
        A[:, 1] = np.minimum(A[:, 1], 7)
        B[:, 1] = np.minimum(B[:, 1], 7)
        got = segments_free(g, A, B)
        want = [reference_free(g.occ, a, b) for a, b in zip(A, B)]
        assert list(got) == want, f"trial {trial}"


def test_float_segments_match_reference():
    rng = np.random.default_rng(11)
    g = random_grid(rng, 8, 8, 0.25)
    A = rng.uniform(0, 8, size=(400, 2))
    B = rng.uniform(0, 8, size=(400, 2))
    got = segments_free(g, A, B)
    want = [reference_free(g.occ, a, b) for a, b in zip(A, B)]
    assert list(got) == want


def test_axis_aligned_and_degenerate_segments_match_reference():
    rng = np.random.default_rng(3)
    g = random_grid(rng, 6, 6, 0.3)
    pts = np.array([[x / 2, y / 2] for x in range(13) for y in range(13)])
    A = pts[rng.integers(0, len(pts), 300)]
    B = A.copy()
    axis = rng.integers(0, 2, 300)
    B[np.arange(300), axis] = rng.integers(0, 13, 300) / 2
    got = segments_free(g, A, B)
    want = [reference_free(g.occ, a, b) for a, b in zip(A, B)]
    assert list(got) == want


def test_resolution_and_origin_are_honoured():
    rows = [[0, 0, 0], [0, 1, 0], [0, 0, 0]]
    g1 = op.GridMap.from_rows(rows)
    g2 = op.GridMap.from_rows(rows, resolution=0.25, origin=(-2.0, 3.0))
    rng = np.random.default_rng(0)
    A = rng.integers(0, 7, size=(100, 2)) / 2
    B = rng.integers(0, 7, size=(100, 2)) / 2
    np.testing.assert_array_equal(segments_free(g1, A, B), segments_free(g2, A * 0.25 + [-2, 3], B * 0.25 + [-2, 3]))


def brute_clearance(occ, p):
    h, w = occ.shape
    best = min(p[0], p[1], w - p[0], h - p[1])
    for iy, ix in zip(*np.nonzero(occ)):
        gap = np.maximum(np.maximum([ix - p[0], iy - p[1]], [p[0] - ix - 1, p[1] - iy - 1]), 0)
        best = min(best, float(np.hypot(*gap)))
    return best


def test_clearance_matches_brute_force():
    rng = np.random.default_rng(5)
    g = random_grid(rng, 15, 12, 0.2)
    P = rng.uniform(0, [12, 15], size=(300, 2))
    free = g.is_free(P)
    got = g.clearance(P)
    for p, f, d in zip(P, free, got):
        if f:
            assert d == pytest.approx(brute_clearance(g.occ, p), abs=1e-12)
        else:
            assert d < 0


def test_clearance_segments_match_brute_force_distance():
    rng = np.random.default_rng(9)
    g = random_grid(rng, 10, 10, 0.15)
    A = rng.uniform(0, 10, size=(300, 2))
    B = A + rng.normal(0, 2.0, size=(300, 2))
    c = 0.3
    got = segments_free(g, A, B, clearance=c)
    # reference: dense sampling is a lower bound on violations; exact rule for c=0 first
    for a, b, ok in zip(A, B, got):
        ts = np.linspace(0, 1, 2001)
        pts = a + ts[:, None] * (b - a)
        inside = np.all((pts >= c - 1e-9) & (pts <= 10 - c + 1e-9))
        dense_min = min(brute_clearance(g.occ, p) for p in pts[::50]) if inside else -1
        if ok:
            # a segment declared clear keeps the clearance at every sample
            assert inside and np.all(g.clearance(pts) >= c - 1e-9)
        elif inside and reference_free(g.occ, a, b):
            # declared not clear: some point must come closer than c (dense sampling finds it)
            assert g.clearance(pts).min() < c + 1e-3 or dense_min < c


def test_validate_path_reports_the_failing_segment():
    g = op.GridMap.from_rows([[0, 0, 0], [0, 1, 0], [0, 0, 0]])
    good = np.array([[0.5, 0.5], [2.5, 0.5], [2.5, 2.5]])
    bad = np.array([[0.5, 0.5], [2.5, 0.5], [0.5, 2.5]])
    assert op.validate_path(g, good)
    chk = op.validate_path(g, bad)
    assert not chk and list(chk.bad_segments) == [1] and "segment 1" in chk.reason
    assert not op.validate_path(g, [[1.5, 1.5]])
    assert not op.validate_path(g, np.array([[0.5, np.nan], [1, 1]]))
    assert not op.validate_path(g, good, clearance=0.6)  # corner cells at 0.5 m from the border


def test_circle_world_rule():
    w = op.CircleWorld((0, 0, 10, 10), [(5, 5, 1.0)], safety=0.5)
    assert w.radii[0] == 1.5
    assert not w.segments_free([0.5, 5], [9.5, 5])
    assert w.segments_free([0.5, 6.5], [9.5, 6.5])            # tangent to the grown circle
    assert not w.segments_free([0.5, 6.5], [9.5, 6.5], clearance=0.01)
    assert not w.is_free([5.0, 6.2]) and w.is_free([5.0, 6.6])
    assert not w.segments_free([-0.1, 1], [2, 2])             # leaves the bounds
    with pytest.raises(op.InfeasibleQueryError):
        w.check_query_point((5, 5), "start")


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 8), st.integers(2, 8), st.integers(0, 2**31 - 1))
def test_segment_rule_is_symmetric_and_matches_reference(h, w, seed):
    rng = np.random.default_rng(seed)
    g = random_grid(rng, h, w, 0.3)
    A = rng.integers(0, 2 * w + 1, size=(20, 2)) / 2.0
    B = rng.integers(0, 2 * w + 1, size=(20, 2)) / 2.0
    A[:, 1] = A[:, 1] * h / w
    B[:, 1] = B[:, 1] * h / w
    A, B = np.round(A * 2) / 2, np.round(B * 2) / 2
    fwd, back = segments_free(g, A, B), segments_free(g, B, A)
    np.testing.assert_array_equal(fwd, back)
    assert list(fwd) == [reference_free(g.occ, a, b) for a, b in zip(A, B)]


def test_worlds_follow_the_world_protocol():
    """Both kinds of world implement the protocol and say which kind they are."""
    from optplan.world import World

    grid = op.GridMap(np.zeros((4, 4), bool))
    circles = op.CircleWorld((0, 0, 4, 4), [(2.0, 2.0, 0.5)])
    assert isinstance(grid, World) and isinstance(circles, World)
    assert grid.is_grid is True and circles.is_grid is False
    assert not isinstance(object(), World)


def test_float_segments_ending_exactly_on_a_grid_line_are_free():
    # a segment from an off-centre point that stops exactly on the edge of a blocked row
    # touches it without entering; float rounding of y(x1) used to push it over the edge
    occ = np.zeros((6, 8), bool)
    occ[3, :] = True
    g = op.GridMap(occ)
    rng = np.random.default_rng(5)
    A = np.column_stack([rng.uniform(0, 8, 500), rng.uniform(0, 3, 500)])
    B = np.column_stack([rng.uniform(0, 8, 500), np.full(500, 3.0)])
    assert segments_free(g, A, B).all()
    assert segments_free(g, B, A).all()
    assert not segments_free(g, A, B + [0.0, 1e-9]).any()
    # same on the transposed map (vertical rule) and as a validated path
    gt = op.GridMap(occ.T.copy())
    assert segments_free(gt, A[:, ::-1], B[:, ::-1]).all()
    assert op.validate_path(g, [[1.4052449648204721, 2.5895367670496596], [4.331689761992734, 3.0]])


def test_wrap_angle_is_one_function_with_a_half_open_interval():
    """One definition serves the simulator, the critics, the mechanisms and the reference DWA."""
    from optplan.local import critics, mechanisms, reference
    from optplan.sim import kinematics
    from optplan.world.geometry import wrap_angle

    assert kinematics.wrap_angle is critics.wrap_angle is mechanisms.wrap_angle is reference.wrap_angle is wrap_angle
    a = np.linspace(-20.0, 20.0, 4001)
    w = wrap_angle(a)
    assert np.all((w >= -np.pi) & (w < np.pi))
    assert np.allclose(np.cos(w), np.cos(a)) and np.allclose(np.sin(w), np.sin(a))
    assert wrap_angle(np.pi) == -np.pi and wrap_angle(-np.pi) == -np.pi and wrap_angle(0.0) == 0.0
