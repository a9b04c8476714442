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
