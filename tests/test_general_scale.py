"""The general encoding on large maps (issue 43 item 3): the local graph and landmarks take
over from all-pairs geodesics over every corner, and every decoded path stays exact-feasible."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.errors import InfeasibleQueryError
from optplan.formulations import encodings as E
from optplan.world.metrics import path_length
from optplan.world.roadmap import LocalGraph, corner_count, h_signature, unreachable_cells
from optplan.worldgen.maps import generate_map, map_query


@pytest.fixture
def landmarks_everywhere(monkeypatch):
    """Every grid map takes the large-map legs (small maps keep the tests fast)."""
    monkeypatch.setattr(E, "EXACT_CORNERS", 0)


@pytest.mark.parametrize("kind,seed", [("random", 3), ("maze", 4), ("rooms", 5)])
def test_landmark_legs_decode_to_feasible_paths_of_their_table_length(landmarks_everywhere, kind, seed):
    grid = generate_map(kind, 48, seed=seed, **({"density": 0.2} if kind == "random" else {}))
    s, g = map_query(grid, seed=seed)
    enc = E.GeneralPath(grid, s, g, m=3)
    assert not enc.exact and len(enc.points) <= 2 * E.LANDMARKS[1]
    X = np.random.default_rng(0).uniform(enc.lower, enc.upper, size=(30, enc.dim))
    P = enc.decode(X)
    np.testing.assert_allclose(path_length(P), enc.leg_length(X), rtol=1e-10)
    assert all(op.validate_path(grid, p).ok for p in P)
    exact = op.shortest_path(grid, s, g, method="visibility").length
    assert enc.leg_length(X).min() >= exact - 1e-9
    # the first corridor drawn is the graph's own shortest way, within a few per cent of the optimum
    first = enc.sample_corridors(5, np.random.default_rng(1))[:1]
    assert enc.leg_length(first)[0] == pytest.approx(enc.table[-2, -1])
    assert enc.table[-2, -1] <= 1.05 * exact


def test_a_plan_on_landmark_legs_is_feasible_and_near_the_optimum(landmarks_everywhere):
    grid = generate_map("random", 40, seed=11, density=0.2)
    s, g = map_query(grid, seed=11)
    r = op.plan(grid, s, g, algorithm="msiar-gwo", encoding="general", max_evals=1500, seed=0)
    exact = op.shortest_path(grid, s, g, method="visibility").length
    assert r.feasible and op.validate_path(grid, r.path).ok
    assert exact - 1e-9 <= r.length <= 1.03 * exact


def test_landmark_legs_keep_the_clearance(landmarks_everywhere):
    grid = generate_map("rooms", 40, seed=8)
    s, g = map_query(grid, seed=8)
    enc = E.GeneralPath(grid, s, g, m=2, clearance=0.2)
    X = np.random.default_rng(2).uniform(enc.lower, enc.upper, size=(20, enc.dim))
    for p in enc.decode(X):
        assert op.validate_path(grid, p, clearance=0.2).ok


def test_a_long_passage_off_the_lattice_is_joined_by_its_grid_line():
    """A 1-cell corridor 60 cells long on a row no lattice point lies on, with no corner inside:
    the consecutive corners at its mouths join along the wall's grid line."""
    rows = np.ones((5, 64), dtype=int)
    rows[2, 1:63] = 0                                   # the corridor (row 2 from the top)
    grid = op.GridMap.from_rows(rows)
    lg = LocalGraph(grid)
    assert lg.radius < 60
    s, g = np.array([1.5, 2.5]), np.array([62.5, 2.5])
    legs = E._LandmarkLegs(grid, s, g, 0.0)
    assert legs.table[-2, -1] == pytest.approx(61.0)


def test_four_connected_regions_decide_unreachable_before_any_graph():
    rows = np.zeros((6, 6), dtype=int)
    rows[:, 3] = 1
    grid = op.GridMap.from_rows(rows)
    assert unreachable_cells(grid, (1.5, 1.5), (4.5, 1.5))
    assert not unreachable_cells(grid, (1.5, 1.5), (2.5, 4.5))
    # a point on the wall's boundary belongs to the free cell it touches, at any origin
    shifted = op.GridMap.from_rows(rows, resolution=0.05, origin=(-3.7, 1.1))
    a = shifted.to_world(np.array([[3.0, 2.5]]))[0]     # on the boundary of the blocked column
    assert not unreachable_cells(shifted, a, shifted.to_world(np.array([[0.5, 0.5]]))[0])
    # two free cells that touch only at a corner are apart
    diag = op.GridMap.from_rows([[0, 1], [1, 0]])
    assert unreachable_cells(diag, (0.5, 1.5), (1.5, 0.5))


def test_an_unreachable_goal_on_a_large_map_is_refused_at_once(landmarks_everywhere):
    rows = np.zeros((30, 30), dtype=int)
    rows[:, 15] = 1
    grid = op.GridMap.from_rows(rows)
    with pytest.raises(InfeasibleQueryError, match="not reachable"):
        E.GeneralPath(grid, np.array([2.5, 2.5]), np.array([27.5, 2.5]))


def test_small_maps_keep_exact_legs():
    grid = generate_map("random", 24, seed=2, density=0.2)
    assert corner_count(grid) <= E.EXACT_CORNERS
    s, g = map_query(grid, seed=2)
    assert E.GeneralPath(grid, s, g).exact


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_shadow_prefilter_of_the_ends_hides_only_refused_segments(seed):
    """What the ends' shadow test hides, the exact rule refuses (at any clearance); and it
    hides most of the far corners of a cluttered map, which is what it is for."""
    grid = op.GridMap.from_rows(generate_map("random", 40, seed=seed, density=0.25).occ[::-1].astype(int),
                                resolution=0.05, origin=(-1.3, 2.7))
    rng = np.random.default_rng(seed)
    free = np.argwhere(~grid.occ)
    p = grid.to_world(free[rng.integers(len(free))][::-1] + rng.uniform(0.05, 0.95, 2))
    lg = LocalGraph(grid)
    d = grid.to_grid(lg.nodes) - grid.to_grid(p[None])[0]
    hidden = E._hidden_from(grid, p, d)
    for c in (0.0, 0.02):
        assert not np.any(hidden & grid.segments_free(np.broadcast_to(p, lg.nodes.shape), lg.nodes, c))
    assert hidden.mean() > 0.5


def test_landmark_rows_are_per_map_and_the_ends_rows_per_query(landmarks_everywhere):
    grid = generate_map("random", 40, seed=12, density=0.2)
    (s1, g1), (s2, g2) = map_query(grid, seed=1), map_query(grid, seed=2)
    a, b = E.GeneralPath(grid, s1, g1), E.GeneralPath(grid, s2, g2)
    assert a.legs.mark_pred is b.legs.mark_pred              # one set of landmark rows for the map
    np.testing.assert_allclose(a.table[:-2, :-2], b.table[:-2, :-2])
    for enc in (a, b):                                        # legs from and to the ends, both ways
        r = enc.reachable
        legs = enc._walk(np.repeat(r, len(r)), np.tile(r, len(r)))
        P = enc.legs.path_points[legs]
        np.testing.assert_allclose(path_length(P), enc.table[np.repeat(r, len(r)), np.tile(r, len(r))],
                                   rtol=1e-9)
        assert np.all(legs[:, 0] == enc.legs.snap_path[np.repeat(r, len(r))])


@pytest.mark.parametrize("seed", [3, 4])
def test_the_class_search_with_lazy_corner_edges_finds_the_roadmaps_class_optimum(monkeypatch, seed):
    """Large maps search the homotopy class over corner edges found as the search goes (no
    roadmap of every edge): the same class optimum as over the roadmap."""
    from optplan.solvers import homotopy as H

    grid = generate_map("random", 32, seed=seed, density=0.2)
    s, g = map_query(grid, seed=seed)
    free = np.argwhere(~grid.occ)
    via = grid.to_world(free[len(free) // 3][::-1] + 0.5)
    a = op.shortest_path(grid, s, via, method="visibility").path
    b = op.shortest_path(grid, via, g, method="visibility").path
    detour = np.vstack([a, b[1:]])
    _, small, _ = H.class_shortest_path(grid, s, g, detour)
    monkeypatch.setattr(H, "ROADMAP_CORNERS", 0)
    path, large, _ = H.class_shortest_path(grid, s, g, detour)
    assert large == pytest.approx(small, rel=1e-9)
    assert op.validate_path(grid, path).ok
    np.testing.assert_array_equal(h_signature(grid, path), h_signature(grid, detour))


def test_class_gaps_say_when_the_class_search_gives_up(monkeypatch):
    from optplan.solvers import homotopy as H
    from optplan.solvers.gaps import class_gaps

    grid = generate_map("random", 32, seed=3, density=0.2)
    s, g = map_query(grid, seed=3)
    free = np.argwhere(~grid.occ)
    via = grid.to_world(free[len(free) // 3][::-1] + 0.5)
    detour = np.vstack([op.shortest_path(grid, s, via, method="visibility").path,
                        op.shortest_path(grid, via, g, method="visibility").path[1:]])
    full = class_gaps(grid, s, g, detour)
    assert full["class_length"] is not None and not full["optimal_class"]
    monkeypatch.setattr(H, "MAX_STATES", 10)
    with pytest.raises(op.ParameterError, match="search states"):
        H.class_shortest_path(grid, s, g, detour)
    cut = class_gaps(grid, s, g, detour)
    assert cut["gap"] == pytest.approx(full["gap"]) and cut["class_length"] is None and cut["class_gap"] is None
