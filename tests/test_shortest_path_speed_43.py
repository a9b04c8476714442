"""The lean ``shortest_path`` of A*/Dijkstra (issue 43 item 4) gives what the full build gave.

A plain query (a ``GridMap``, no clearance, start and goal as plain pairs of numbers) now
checks its points on Python floats, judges the returned path by the exact rule in cell units
(``geometry.centre_moves_free``, ``geometry.in_free_cell``) and leaves the turn metrics and
``min_clearance`` to their first read; the A* loop pushes an expansion's last entry together
with the next pop. Everything here is compared with a fresh reference: the general segment
rule, ``validate_path`` and ``path_metrics`` on the returned path, the full query path
(a numpy-scalar clearance takes it), scipy's Dijkstra and a plain A* loop. No timing.
"""
from __future__ import annotations

import copy
import dataclasses
import heapq
import math
import pickle

import numpy as np
import pytest

import optplan as op
from optplan.errors import InfeasibleQueryError, OptplanError
from optplan.results import PlanResult
from optplan.solvers.graph import shortest_path
from optplan.solvers.graph.astar import astar_cells, octile
from optplan.solvers.gridpath.moves import move_table
from optplan.solvers.result import make_plan_result
from optplan.world.geometry import (centre_moves_free, grid_point_free, in_free_cell, points_free, segments_free,
                                    validate_path)
from optplan.world.metrics import path_metrics


def seeded_map(seed: int, density: float = 0.25) -> op.GridMap:
    rng = np.random.default_rng(seed)
    res, origin = ((1.0, (0.0, 0.0)), (0.5, (1.0, -2.0)), (0.25, (-3.5, 7.25)), (0.1, (0.3, 0.7)))[seed % 4]
    occ = rng.random((9 + seed % 11, 13 - seed % 5)) < density
    return op.GridMap(occ, resolution=res, origin=origin)


def query_points(grid, rng, n: int):
    """Points in grid units of every kind the lean path meets: centres, inner points, points on
    cell edges and lattice vertices, quarter points, and a few outside the map."""
    W, H = grid.width, grid.height
    kinds = [lambda: rng.integers(0, [W, H]) + 0.5, lambda: rng.uniform(0, [W, H]),
             lambda: rng.integers(0, [W + 1, H + 1]).astype(float),
             lambda: rng.integers(0, [W, H]) + rng.choice([0.0, 0.25, 0.5], 2),
             lambda: rng.uniform(-0.3, [W + 0.3, H + 0.3])]
    return [kinds[int(rng.integers(len(kinds)))]() for _ in range(n)]


def as_given(p: np.ndarray, form: int):
    """A point as callers write it: an array, a tuple, a list."""
    return (p, tuple(p.tolist()), list(p.tolist()))[form % 3]


def full_query(grid, s, g, **kw) -> PlanResult:
    """The query through the full path (``check_start_goal``, ``cell_path``, ``make_plan_result``):
    a clearance given as a numpy scalar is not a plain number."""
    return shortest_path(grid, s, g, clearance=np.float64(0.0), **kw)


def reference(grid, r: PlanResult) -> PlanResult:
    """The result computed plainly from the returned path: the exact check, every metric."""
    check = validate_path(grid, r.path)
    m = path_metrics(grid, r.path)
    msg = r.message if check else r.message.split("; infeasible")[0] + f"; infeasible: {check.reason}"
    return PlanResult(r.algorithm, r.path.copy(), bool(check), m.length, m.turn_angle_deg, m.n_turns,
                      m.min_clearance, r.runtime_s, np.zeros(0), False, None, msg, 0)


def same(a: PlanResult, b: PlanResult) -> None:
    da, db = a.to_dict(), b.to_dict()
    da.pop("runtime_s"), db.pop("runtime_s")
    assert da == db
    assert np.array_equal(a.path, b.path) and a.path.dtype == b.path.dtype == np.float64


# ------------------------------------------------------------------ the rule in cell units
@pytest.mark.parametrize("seed", range(12))
def test_centre_moves_free_gives_the_rule_s_verdicts(seed):
    rng = np.random.default_rng(seed)
    shape = [(1, 6), (2, 5), (6, 1), (3, 2)][seed % 4] if seed < 4 else (4 + seed % 5, 3 + seed % 6)
    grid = op.GridMap(rng.random(shape) < 0.4, resolution=(1.0, 0.3)[seed % 2], origin=(seed * 0.7, -1.3))
    W, H = grid.width, grid.height
    centres = grid.cell_center(np.stack(np.divmod(np.arange(W * H), W)[::-1], axis=1))
    a, b = np.meshgrid(np.arange(W * H), np.arange(W * H), indexing="ij")
    a, b = a.ravel(), b.ravel()
    keep = a != b
    a, b = a[keep], b[keep]
    got = np.array([centre_moves_free(grid, [i, j])[0] for i, j in zip(a, b)])
    rule = segments_free(grid, centres[a], centres[b])
    adjacent = (np.abs(a % W - b % W) <= 1) & (np.abs(a // W - b // W) <= 1)
    assert not got[~adjacent].any()                 # undecided: the general rule's business
    if W >= 3:
        assert np.array_equal(got[adjacent], rule[adjacent])
    else:                                           # 1 or 2 wide: never a wrong "free"
        assert not (got & ~rule).any()
    # a whole sequence at once is the pairs one by one; indices off the map are not free
    seq = rng.integers(0, W * H, 30)
    assert np.array_equal(centre_moves_free(grid, seq), [centre_moves_free(grid, seq[k:k + 2])[0] for k in range(29)])
    assert not centre_moves_free(grid, [-1, 0]).any() and not centre_moves_free(grid, [0, W * H]).any()
    assert centre_moves_free(grid, [0]).shape == (0,)


@pytest.mark.parametrize("seed", range(8))
def test_point_checks_in_cell_units_match_the_rule(seed):
    grid = seeded_map(seed, 0.35)
    rng = np.random.default_rng(50 + seed)
    W = grid.width
    for q in query_points(grid, rng, 150):
        p = grid.to_world(q)
        gq = grid.point_to_grid(*p.tolist())
        assert grid_point_free(grid, *gq) == bool(points_free(grid, p))
        for cell in range(W * grid.height):
            if in_free_cell(grid, *gq, cell):
                iy, ix = divmod(cell, W)
                other = grid.to_world(rng.uniform([ix, iy], [ix + 1, iy + 1]))
                assert segments_free(grid, [p, p], [grid.cell_center((ix, iy)), other]).all()
                assert not grid.occ[iy, ix]


# ------------------------------------------------------------------ the whole call
QUERIES = [(seed, method, cc) for seed in range(10) for method in ("astar", "dijkstra") for cc in (False, True)]


@pytest.mark.parametrize("seed, method, corner_cutting", QUERIES)
def test_lean_call_equals_the_full_call_and_the_plain_reference(seed, method, corner_cutting):
    grid = seeded_map(seed)
    rng = np.random.default_rng(200 + seed)
    pts = query_points(grid, rng, 24)
    done = refused = 0
    for k, (qs, qg) in enumerate(zip(pts[::2], pts[1::2])):
        s, g = grid.to_world(qs), grid.to_world(qg)
        kw = dict(method=method, corner_cutting=corner_cutting)
        try:
            full = full_query(grid, s, g, **kw)
        except OptplanError as exc:
            with pytest.raises(type(exc)) as lean_exc:
                shortest_path(grid, as_given(s, k), as_given(g, k + 1), **kw)
            assert str(lean_exc.value) == str(exc)
            refused += 1
            continue
        lean = shortest_path(grid, as_given(s, k), as_given(g, k + 1), **kw)
        same(lean, full)
        same(lean, reference(grid, lean))
        assert lean.feasible == bool(validate_path(grid, lean.path))
        done += 1
    assert done


# outside, on the border, just outside within GridMap.to_grid's snapping of the border (outside
# all the same), not numbers, not finite, not a pair, numbers the lean check leaves to the full one
BAD_POINTS = [(-0.5, 1.0), (1.0, 1e9), (3.0, 3.0), (0.0, 0.0), (3.0 + 1e-12, 1.5), (-1e-12, 1.5),
              (1.5, 3.0 + 1e-12), (math.nan, 1.0), (math.inf, 0.5), (True, 1.0), (2**60, 1.0), (1, 2, 3),
              np.array([0.5, 0.5], dtype=np.float32), np.array([[0.5], [0.5]]), "ab", None]


@pytest.mark.parametrize("bad", BAD_POINTS + ["blocked", "same"])
def test_refused_and_odd_points_get_what_the_full_check_gives(bad):
    grid = op.GridMap(np.array([[0, 0, 1], [0, 0, 0], [1, 0, 0]], dtype=bool))
    good = (0.5, 0.5)
    bad = {"blocked": (2.5, 0.5), "same": good}.get(bad, bad) if isinstance(bad, str) else bad
    for s, g in ((bad, (2.5, 2.5)), (good, bad)):
        try:
            full = full_query(grid, s, g)
        except OptplanError as exc:
            with pytest.raises(type(exc)) as lean_exc:
                shortest_path(grid, s, g)
            assert str(lean_exc.value) == str(exc)
        else:
            same(shortest_path(grid, s, g), full)


def test_node_to_node_lengths_are_the_octile_optimum_and_no_shorter_than_the_exact_one():
    from scipy.sparse.csgraph import dijkstra

    for seed in range(6):
        grid = seeded_map(seed, 0.2)
        W = grid.width
        table = move_table(grid)
        free = np.flatnonzero(~grid.occ.ravel())
        rng = np.random.default_rng(seed)
        for a, b in rng.choice(free, (5, 2)):
            if a == b:
                continue
            s, g = (grid.cell_center((c % W, c // W)) for c in (a, b))
            D = dijkstra(table.csr, indices=int(a))[int(b)]
            if not np.isfinite(D):
                with pytest.raises(InfeasibleQueryError):
                    shortest_path(grid, s, g)
                continue
            r = shortest_path(grid, s, g)
            assert r.feasible and math.isclose(r.length, D * grid.resolution, rel_tol=1e-12)
            exact = shortest_path(grid, s, g, method="visibility")
            assert r.length >= exact.length - 1e-9


def test_a_path_through_an_obstacle_is_still_infeasible():
    # corner cutting passes between the two blocked cells of a diagonal: the one exact rule refuses
    grid = op.GridMap(np.array([[0, 1], [1, 0]], dtype=bool))
    r = shortest_path(grid, (0.5, 0.5), (1.5, 1.5), corner_cutting=True)
    check = validate_path(grid, r.path)
    assert not r.feasible and not check
    assert r.message.endswith("infeasible: " + check.reason)
    assert not centre_moves_free(grid, [0, 3]).any()
    # a path through a blocked cell, however it is built
    grid = op.GridMap(np.array([[0, 1, 0]], dtype=bool))
    P = grid.cell_center(np.array([(0, 0), (1, 0), (2, 0)]))
    assert not centre_moves_free(grid, [0, 1, 2]).any()
    assert not make_plan_result(grid, P, "astar", 0.0, defer_clearance=True).feasible
    with pytest.raises(InfeasibleQueryError):
        shortest_path(grid, (0.5, 0.5), (2.5, 0.5))


def test_the_lean_path_is_taken_and_the_general_check_only_when_needed(monkeypatch):
    from optplan.solvers import result as result_module

    calls = []   # runs of the general rule (the result is built in one place either way)
    real = result_module.validate_path_segments
    monkeypatch.setattr(result_module, "validate_path_segments", lambda *a, **k: calls.append(1) or real(*a, **k))
    grid = op.GridMap(np.zeros((9, 12), dtype=bool), resolution=0.5, origin=(1.0, -2.0))
    s, g = grid.cell_center((0, 0)), grid.cell_center((11, 4))
    for args in ((s, g), (tuple(s), list(g)), (s + 0.1 * grid.resolution, g - 0.2 * grid.resolution)):
        assert shortest_path(grid, *args).feasible
    assert not calls
    shortest_path(grid, s, g, clearance=0.1)               # a clearance: the general build
    assert len(calls) == 1
    blocked = op.GridMap(np.array([[0, 1], [1, 0]], dtype=bool))
    shortest_path(blocked, (0.5, 0.5), (1.5, 1.5), corner_cutting=True)
    assert len(calls) == 2


# ------------------------------------------------------------------ fields read later
def test_deferred_fields_give_the_eager_values_every_way_they_are_read():
    occ = np.zeros((8, 10), dtype=bool)
    occ[2:6, 4] = occ[5, 1:5] = True
    grid = op.GridMap(occ, resolution=0.5, origin=(1.0, -2.0))
    s, g = grid.to_world((0.3, 7.6)), grid.to_world((9.2, 0.4))
    base = shortest_path(grid, s, g)
    eager = reference(grid, base)
    assert base.feasible and base.n_turns > 1 and len(base.path) > 4

    def fresh():
        return shortest_path(grid, s, g)

    readers = [lambda r: (r.turn_angle_deg, r.n_turns, r.min_clearance), lambda r: r.to_dict(),
               lambda r: r.to_json_dict(), repr, lambda r: pickle.loads(pickle.dumps(r)),
               copy.copy, copy.deepcopy, lambda r: dataclasses.replace(r, seed=1)]
    for read in readers:
        r = fresh()
        read(r)
        assert (r.turn_angle_deg, r.n_turns, r.min_clearance) == (eager.turn_angle_deg, eager.n_turns,
                                                                   eager.min_clearance)
    same(fresh(), eager)
    r = fresh()
    r.path[1:-1] += 0.01                  # edited in place before a deferred field is read
    assert (r.turn_angle_deg, r.n_turns, r.min_clearance) == (eager.turn_angle_deg, eager.n_turns, eager.min_clearance)
    r = fresh()
    r.n_turns = 99                        # assigned before it is read: the assignment stands
    assert r.n_turns == 99 and r.turn_angle_deg == eager.turn_angle_deg


# ------------------------------------------------------------------ the A* loop
def plain_astar(table, sources, targets, source_bias=None, target_bias=None):
    """The A* loop with one push and one pop per entry (what ``astar_cells`` did before it
    paired an expansion's last push with the next pop), on the same heuristic and keys."""
    W, n = table.width, table.width * table.height
    targets = [int(t) for t in targets]
    ay, ax = divmod(targets[0], W)
    slack = max(octile(t % W - ax, t // W - ay) for t in targets) if len(targets) > 1 else 0.0
    H = table.octile_window[table.height - 1 - ay:2 * table.height - 1 - ay, W - 1 - ax:2 * W - 1 - ax]
    H = list(np.maximum(H - slack, 0.0).ravel() if slack > 0 else H.ravel()) + [0.0]
    dist, parent, closed = [math.inf] * (n + 1), [-1] * (n + 1), set()
    extra = dict(zip(targets, target_bias or [0.0] * len(targets)))
    heap = []
    for s, b in zip(sources, source_bias or [0.0] * len(sources)):
        dist[int(s)] = float(b)
        heapq.heappush(heap, (H[int(s)] + float(b), float(b), int(s)))
    while heap:
        _, d, c = heapq.heappop(heap)
        if c in closed or d != dist[c]:
            continue
        if c == n:
            c = parent[n]
            break
        if c in extra:
            if len(targets) == 1:
                d += extra[c]
                break
            closed.add(c)
            if d + extra[c] < dist[n]:
                dist[n], parent[n] = d + extra[c], c
                heapq.heappush(heap, (dist[n], dist[n], n))
            continue
        closed.add(c)
        for off, w in table.moves_by_mask[table.masks[c]]:
            t = c + off
            if t not in closed and d + w < dist[t] - 1e-12:
                dist[t], parent[t] = d + w, c
                heapq.heappush(heap, (d + w + H[t], d + w, t))
    else:
        return None
    cells = [c]
    while parent[cells[-1]] >= 0:
        cells.append(parent[cells[-1]])
    return cells[::-1], d


@pytest.mark.parametrize("seed", range(6))
def test_astar_pops_in_the_plain_loop_s_order(seed):
    rng = np.random.default_rng(seed)
    for k in range(15):
        occ = rng.random((5 + (seed * 7 + k) % 23, 5 + (seed + k) % 17)) < rng.uniform(0.0, 0.4)
        free = np.flatnonzero(~occ.ravel())
        if len(free) < 6:
            continue
        table = move_table(op.GridMap(occ), bool(k % 2))
        for _ in range(4):
            ns, nt = rng.integers(1, 4, 2)
            src, tgt = (rng.choice(free, m, replace=False).tolist() for m in (ns, nt))
            sb = (rng.integers(0, 2, ns) * 1e-9).tolist() if rng.random() < 0.5 else None
            tb = (rng.integers(0, 2, nt) * 1e-9).tolist() if rng.random() < 0.5 else None
            got, ref = astar_cells(table, src, tgt, sb, tb), plain_astar(table, src, tgt, sb, tb)
            if ref is None:
                assert got is None
            else:
                assert got[0] == ref[0] and got[1] == ref[1]
