"""Graph baselines against published optima: Moving AI octile lengths and Anya any-angle costs."""
from __future__ import annotations

import csv
import re

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import optplan as op
from optplan.solvers.graph import shortest_path
from optplan.world.loaders import load_scen
from optplan.world.metrics import path_length

from conftest import random_grid

MAPS = {"arena": "movingai/dao/arena.map", "den312d": "movingai/dao/den312d.map",
        "room": "movingai/mapf/room-32-32-4.map"}
ANYA = {"arena": "movingai/dao/arena.map.anya.csv", "den312d": "movingai/dao/den312d.map.anya.csv",
        "room": "movingai/mapf/room-32-32-4-random-1.anya.csv"}


@pytest.mark.parametrize("name", ["arena", "den312d"])
def test_astar_matches_every_scen_optimum(shared_data, name):
    grid = op.load_map(shared_data / MAPS[name])
    rows = load_scen(shared_data / f"{MAPS[name]}.scen")
    assert len(rows) > 100
    for e in rows:
        r = shortest_path(grid, e.start_world(), e.goal_world(), method="astar")
        assert r.length == pytest.approx(e.optimal, abs=1e-3), e
        assert r.feasible


def test_dijkstra_equals_astar(shared_data):
    grid = op.load_map(shared_data / MAPS["arena"])
    for e in load_scen(shared_data / f"{MAPS['arena']}.scen")[::10]:
        a = shortest_path(grid, e.start_world(), e.goal_world(), method="astar")
        d = shortest_path(grid, e.start_world(), e.goal_world(), method="dijkstra")
        assert a.length == pytest.approx(d.length, abs=1e-9)


def _anya_rows(path):
    with open(path) as fh:
        for row in csv.DictReader(fh, delimiter=";"):
            s = tuple(int(v) for v in re.findall(r"-?\d+", row["start"]))
            t = tuple(int(v) for v in re.findall(r"-?\d+", row["target"]))
            yield s, t, float(row["realcost"])


def _is_double_corner(grid, x: int, y_world: int) -> bool:
    pad = grid.padded
    bl, br, tl, tr = pad[y_world, x], pad[y_world, x + 1], pad[y_world + 1, x], pad[y_world + 1, x + 1]
    return bool((bl and tr and not br and not tl) or (br and tl and not bl and not tr))


@pytest.mark.parametrize("name", ["arena", "den312d", "room"])
def test_visibility_corner_mode_reproduces_anya(shared_data, name):
    grid = op.load_map(shared_data / MAPS[name])
    H = grid.height
    checked = 0
    for (sx, sy), (tx, ty), cost in _anya_rows(shared_data / ANYA[name]):
        s, t = (sx, H - sy), (tx, H - ty)
        if _is_double_corner(grid, *s) or _is_double_corner(grid, *t):
            continue
        r = shortest_path(grid, s, t, method="visibility", points="corners")
        assert r.length == pytest.approx(cost, abs=1e-9), (s, t)
        assert r.feasible and path_length(r.path) == pytest.approx(r.length, abs=1e-9)
        checked += 1
    assert checked > 100


@pytest.mark.parametrize("name", ["arena", "room"])
def test_visibility_centre_mode_never_longer_than_octile(shared_data, name):
    grid = op.load_map(shared_data / MAPS[name])
    scen = shared_data / (f"{MAPS[name]}.scen" if name != "room" else "movingai/mapf/room-32-32-4-random-1.scen")
    for e in load_scen(scen)[::4]:
        r = shortest_path(grid, e.start_world(), e.goal_world(), method="visibility")
        assert r.feasible and op.validate_path(grid, r.path)
        assert r.length <= e.optimal + 1e-4  # scen optima are printed to 4 decimals


def test_corner_cutting_matches_the_reference_table(shared_data):
    with open(shared_data / "papermaps/reference_lengths_computed_here.csv", newline="") as f:
        table = list(csv.DictReader(f))
    assert len(table) >= 14
    for row in table:
        grid = op.load_map(shared_data / "papermaps" / f"{row['map']}.txt")
        n = grid.height
        (r0, c0), (r1, c1) = (tuple(int(v) for v in re.findall(r"\d+", row[k])) for k in ("start_rc", "goal_rc"))
        # (row, col) as written, row 1 = top -> cell centre in metres
        s = (c0 - 0.5, n - r0 + 0.5)
        g = (c1 - 0.5, n - r1 + 0.5)
        cut = shortest_path(grid, s, g, method="astar", corner_cutting=True)
        nocut = shortest_path(grid, s, g, method="astar")
        vis = shortest_path(grid, s, g, method="visibility")
        assert cut.length == pytest.approx(float(row["len_8conn_corner_cutting_G2D"]), abs=1e-3), row
        assert nocut.length == pytest.approx(float(row["len_8conn_no_corner_cutting"]), abs=1e-3), row
        assert vis.length == pytest.approx(float(row["len_anyangle_cell_centres"]), abs=1e-3), row
        # a corner-cutting path may squeeze between diagonal blocks: the exact check says so
        assert nocut.feasible and vis.feasible


def test_bad_queries_raise_infeasible():
    grid = op.GridMap.from_rows([[0, 1, 0], [0, 1, 0], [0, 1, 0]])
    with pytest.raises(op.InfeasibleQueryError, match="blocked"):
        shortest_path(grid, (1.5, 1.5), (0.5, 0.5))
    with pytest.raises(op.InfeasibleQueryError, match="outside"):
        shortest_path(grid, (0.5, 0.5), (5.0, 0.5))
    for method in ("astar", "visibility"):
        with pytest.raises(op.InfeasibleQueryError, match="unreachable"):
            shortest_path(grid, (0.5, 0.5), (2.5, 2.5), method=method)
    with pytest.raises(op.UnknownAlgorithmError):
        shortest_path(grid, (0.5, 0.5), (0.5, 2.5), method="bfs")


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 12), st.integers(2, 12), st.floats(0.0, 0.4), st.integers(0, 2**31 - 1))
def test_random_maps_paths_validate_and_visibility_is_shortest(h, w, density, seed):
    rng = np.random.default_rng(seed)
    grid = random_grid(rng, h, w, density)
    free = np.argwhere(~grid.occ)
    if len(free) < 2:
        return
    (sy, sx), (gy, gx) = free[rng.choice(len(free), 2, replace=False)]
    s, g = (sx + 0.5, sy + 0.5), (gx + 0.5, gy + 0.5)
    try:
        a = shortest_path(grid, s, g, method="astar")
    except op.InfeasibleQueryError:
        with pytest.raises(op.InfeasibleQueryError):
            shortest_path(grid, s, g, method="visibility")
        return
    v = shortest_path(grid, s, g, method="visibility")
    assert a.feasible and v.feasible
    assert op.validate_path(grid, a.path) and op.validate_path(grid, v.path)
    assert v.length <= a.length + 1e-9
    assert v.length >= np.hypot(gx - sx, gy - sy) - 1e-9


# ---------------------------------------------------------------- exact ends (issue 29)
def _double_corner_vertices(grid) -> np.ndarray:
    pad = grid.padded
    bl, br, tl, tr = pad[:-1, :-1], pad[:-1, 1:], pad[1:, :-1], pad[1:, 1:]
    return (bl & tr & ~br & ~tl) | (br & tl & ~bl & ~tr)  # [Y, X] over the lattice vertices


def exact_segment_free(grid, p, q) -> bool:
    """The segment rule of DESIGN.md in exact rational arithmetic (fractions), written
    independently of ``optplan.world.geometry``: the closed segment stays in the map,
    enters no open blocked square, runs along no edge between two blocked squares and
    has no double corner strictly inside. Grid units, resolution 1, origin 0."""
    from fractions import Fraction as F

    (px, py), (qx, qy) = (F(float(v)) for v in p), (F(float(v)) for v in q)
    W, H = grid.width, grid.height
    if not all(0 <= v <= m for v, m in ((px, W), (qx, W), (py, H), (qy, H))):
        return False
    dx, dy = qx - px, qy - py
    if dx == dy == 0:
        return bool(grid.is_free(np.asarray(p, float)))

    def blocked(ix, iy):
        return not (0 <= ix < W and 0 <= iy < H) or bool(grid.occ[iy, ix])

    def open_interval(p0, d, lo, hi):  # t in [0, 1] with p0 + t d strictly inside (lo, hi)
        if d == 0:
            return (F(0), F(1)) if lo < p0 < hi else None
        a, b = sorted(((lo - p0) / d, (hi - p0) / d))
        return (max(a, F(0)), min(b, F(1)))

    x0, x1 = int(min(px, qx)) - 1, int(max(px, qx)) + 1
    y0, y1 = int(min(py, qy)) - 1, int(max(py, qy)) + 1
    for ix in range(x0, x1 + 1):
        for iy in range(y0, y1 + 1):
            if not blocked(ix, iy):
                continue
            a, b = open_interval(px, dx, ix, ix + 1), open_interval(py, dy, iy, iy + 1)
            if a and b and max(a[0], b[0]) < min(a[1], b[1]):
                return False  # enters the open square
            if a and b is None and dy == 0 and py == iy + 1 and blocked(ix, iy + 1) and a[0] < a[1]:
                return False  # along the edge above a blocked square, with a blocked square above
            if b and a is None and dx == 0 and px == ix + 1 and blocked(ix + 1, iy) and b[0] < b[1]:
                return False
    for X in range(max(x0, 0), min(x1, W) + 1):
        for Y in range(max(y0, 0), min(y1, H) + 1):
            bl, br, tl, tr = blocked(X - 1, Y - 1), blocked(X, Y - 1), blocked(X - 1, Y), blocked(X, Y)
            if not ((bl and tr and not br and not tl) or (br and tl and not bl and not tr)):
                continue
            if (X - px) * dy != (Y - py) * dx:
                continue
            t = (X - px) / dx if dx else (Y - py) / dy
            if 0 < t < 1:
                return False  # through a double corner
    return True


def brute_force_any_angle(grid, s, g) -> float:
    """Dijkstra (scipy) over the complete visibility graph of every free, non-double lattice
    vertex plus start and goal: the any-angle optimum. Pairs of lattice vertices are checked by
    ``segments_free`` (integer-exact there), pairs with an end by :func:`exact_segment_free`."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra

    Y, X = np.nonzero(~_double_corner_vertices(grid))
    V = np.stack([X, Y], axis=1).astype(float) * grid.resolution + grid.origin
    V = V[grid.is_free(V)]
    P = np.vstack([s, g, V])
    I, J = np.triu_indices(len(P), 1)
    ok = grid.segments_free(P[I], P[J])
    for k in np.nonzero(I < 2)[0]:
        ok[k] = exact_segment_free(grid, P[I[k]], P[J[k]])
    W = np.zeros((len(P), len(P)))
    W[I[ok], J[ok]] = np.hypot(*(P[J[ok]] - P[I[ok]]).T)
    d = dijkstra(csr_matrix(W), directed=False, indices=0)  # sparse: a dense input drops weights < 1e-8
    return float(d[1])


def brute_force_cell_graph(grid, s, g) -> float:
    """The A* graph written out densely: free cell centres with the 8 moves (diagonals need
    both side cells free), start and goal joined to the centres of the free cells whose closed
    square holds them when the segment is free, and to each other when they share a free cell."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra

    iy, ix = np.nonzero(~grid.occ)
    C = np.stack([ix, iy], axis=1)
    n = len(C)
    W = np.zeros((n + 2, n + 2))
    for a in range(n):
        for b in range(n):
            dx, dy = C[b] - C[a]
            if max(abs(dx), abs(dy)) != 1:
                continue
            if dx and dy and (grid.occ[C[a][1], C[a][0] + dx] or grid.occ[C[a][1] + dy, C[a][0]]):
                continue
            W[a, b] = np.hypot(dx, dy) * grid.resolution
    centres = grid.cell_center(C)

    def holds(p):  # which free cells' closed squares hold p
        q = grid.to_grid(p)
        return np.all((C <= q) & (q <= C + 1), axis=1)

    for k, p in ((n, s), (n + 1, g)):
        for a in np.nonzero(holds(p))[0]:
            if grid.segments_free(p, centres[a]):
                W[k, a] = W[a, k] = max(np.hypot(*(centres[a] - p)), 1e-300)
    if np.any(holds(s) & holds(g)) and grid.segments_free(s, g):
        W[n, n + 1] = np.hypot(*(g - s))
    return float(dijkstra(csr_matrix(W), directed=False, indices=n)[n + 1])


def _random_query(rng, grid, where="inside"):
    free = np.argwhere(~grid.occ)
    (sy, sx), (gy, gx) = free[rng.choice(len(free), 2, replace=False)]
    if where == "inside":
        off = rng.uniform(0.02, 0.98, (2, 2))
    else:  # on a cell edge or corner of the chosen free cell
        off = rng.choice([0.0, 0.5, 1.0], (2, 2))
    return np.array([sx, sy]) + off[0], np.array([gx, gy]) + off[1]


@pytest.mark.parametrize("seed", range(40))
def test_off_centre_queries_are_exact(seed):
    """Random off-centre queries: ends kept exactly, visibility equals the brute-force any-angle
    optimum, A* and Dijkstra equal the brute-force cell-centre graph."""
    rng = np.random.default_rng(seed)
    h, w = rng.integers(3, 9, 2)
    grid = random_grid(rng, h, w, rng.uniform(0.1, 0.4))
    if (~grid.occ).sum() < 2:
        return
    s, g = _random_query(rng, grid, "inside" if seed % 2 else "lattice")
    if not (grid.is_free(s) and grid.is_free(g)) or np.array_equal(s, g):
        return
    best = brute_force_any_angle(grid, s, g)
    cells = brute_force_cell_graph(grid, s, g)
    if not np.isfinite(best):
        with pytest.raises(op.InfeasibleQueryError):
            shortest_path(grid, s, g, method="visibility")
        return
    v = shortest_path(grid, s, g, method="visibility")
    assert v.length == pytest.approx(best, abs=1e-9)
    assert np.array_equal(v.path[0], s) and np.array_equal(v.path[-1], g)
    assert all(exact_segment_free(grid, a, b) for a, b in zip(v.path[:-1], v.path[1:]))
    for method in ("astar", "dijkstra"):
        if not np.isfinite(cells):
            with pytest.raises(op.InfeasibleQueryError):
                shortest_path(grid, s, g, method=method)
            continue
        r = shortest_path(grid, s, g, method=method)
        assert np.array_equal(r.path[0], s) and np.array_equal(r.path[-1], g), method
        assert r.length == pytest.approx(cells, abs=1e-9), method
        assert v.length <= r.length + 1e-9
        assert not (corner_cut := op.validate_path(grid, r.path)) or r.feasible, corner_cut


def test_start_on_a_free_cell_corner_is_accepted():
    # the start (1, 1) is the corner of free cell (0, 0); the cell up-right of it, (1, 1), is blocked
    grid = op.GridMap.from_rows([[0, 0, 0, 0],
                                 [0, 0, 0, 0],
                                 [0, 1, 0, 0],
                                 [0, 0, 0, 0]])
    for method in ("astar", "dijkstra", "visibility"):
        r = shortest_path(grid, (1.0, 1.0), (3.5, 3.5), method=method)
        assert r.feasible and tuple(r.path[0]) == (1.0, 1.0) and tuple(r.path[-1]) == (3.5, 3.5), method
    # the top-right corner of the map and a point on the left border
    for method in ("astar", "dijkstra", "visibility"):
        r = shortest_path(grid, (0.0, 2.3), (4.0, 4.0), method=method)
        assert r.feasible and tuple(r.path[0]) == (0.0, 2.3) and tuple(r.path[-1]) == (4.0, 4.0), method


def test_cell_centre_queries_keep_their_lengths():
    """Ends at cell centres: the path is the centre sequence (one point per cell), as before."""
    grid = op.GridMap.from_rows([[0, 0, 0, 0, 0],
                                 [0, 1, 1, 1, 0],
                                 [0, 0, 0, 1, 0],
                                 [1, 1, 0, 1, 0],
                                 [0, 0, 0, 0, 0]])
    for method in ("astar", "dijkstra"):
        r = shortest_path(grid, (0.5, 0.5), (2.5, 2.5), method=method)
        # (0,0) (1,0) (2,0) (2,1) (2,2): the diagonal (1,0)->(2,1) would cut the blocked (1,1)
        assert r.length == pytest.approx(4.0) and len(r.path) == 5, method
    v = shortest_path(grid, (0.5, 0.5), (2.5, 2.5), method="visibility", points="centres")
    # (0.5,0.5) -> corner (2,1) -> (2.5,2.5)
    assert v.length == pytest.approx(np.hypot(1.5, 0.5) + np.hypot(0.5, 1.5), abs=1e-12)


def test_visibility_with_clearance_starts_in_a_border_cell():
    grid = op.GridMap.from_rows([[0, 0, 0, 0, 0, 0],
                                 [0, 0, 0, 0, 0, 0],
                                 [0, 0, 0, 1, 0, 0],
                                 [0, 0, 0, 1, 0, 0],
                                 [0, 0, 0, 1, 0, 0]])
    s, g = (0.5, 0.5), (5.5, 0.5)
    for method in ("astar", "visibility"):
        r = shortest_path(grid, s, g, method=method, clearance=0.3)
        assert r.feasible and tuple(r.path[0]) == s and tuple(r.path[-1]) == g, method
        assert op.validate_path(grid, r.path, 0.3)


def test_points_convention_is_checked_never_applied():
    grid = op.GridMap(np.zeros((4, 4), bool))
    with pytest.raises(op.ParameterError, match="not the centre of a cell"):
        shortest_path(grid, (0.3, 0.5), (3.5, 3.5), method="visibility", points="centres")
    with pytest.raises(op.ParameterError, match="lattice vertex"):
        shortest_path(grid, (0.5, 0.5), (3.0, 3.0), method="visibility", points="corners")
    with pytest.raises(op.ParameterError, match="points must be"):
        shortest_path(grid, (0.5, 0.5), (3.0, 3.0), method="visibility", points="snap")


def test_visibility_blocks_and_prunings_keep_the_optimum(monkeypatch):
    """Tiny segment batches and no sampled rejection give the same any-angle optimum."""
    from optplan.solvers.graph import visibility as V
    from optplan.world import geometry as G

    rng = np.random.default_rng(11)
    grid = random_grid(rng, 24, 24, 0.25)
    free = np.argwhere(~grid.occ)
    (sy, sx), (gy, gx) = free[0], free[-1]
    s, g = (sx + 0.31, sy + 0.62), (gx + 0.77, gy + 0.14)
    try:
        ref = shortest_path(grid, s, g, method="visibility")
    except op.InfeasibleQueryError:
        pytest.skip("this seed's corners are not connected")
    monkeypatch.setattr(G, "SPAN_BUDGET", 10)
    monkeypatch.setattr(V, "SAMPLE_BUDGET", 40)
    assert shortest_path(grid, s, g, method="visibility").length == pytest.approx(ref.length, abs=1e-12)
    monkeypatch.setattr(V, "SAMPLE_STEPS", np.zeros(0))
    assert shortest_path(grid, s, g, method="visibility").length == pytest.approx(ref.length, abs=1e-12)
    assert ref.length == pytest.approx(brute_force_any_angle(grid, np.array(s), np.array(g)), abs=1e-9)


def test_ties_between_end_cells_go_to_the_cell_the_point_belongs_to():
    """A start on the edge between rows 3 and 4 joins both cells at the same cost; the path
    goes through row 4, the cell that holds (0.5, 4.0) under the half-open convention (the
    cell the search used to snap to), for A* and at the goal end for Dijkstra too."""
    grid = op.GridMap(np.zeros((8, 12), bool))
    a = shortest_path(grid, (0.5, 4.0), (11.5, 4.0), method="astar")
    assert a.path[:, 1].tolist() == [4.0] + [4.5] * 12 + [4.0]
    d = shortest_path(grid, (0.5, 4.0), (11.5, 4.0), method="dijkstra")
    assert d.length == pytest.approx(a.length) and d.path[-2, 1] == 4.5
