"""li2023's TGA / IGA on the paper's cell-sequence chromosome (optplan.solvers.gridpath.cell_ga)."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.solvers.gridpath.cell_ga import drop_loops
from optplan.world.geometry import validate_path
from optplan.world.grid import GridMap


def serpentine() -> GridMap:
    """7x7 grid whose only corridor runs right, up, left (back in x), up, right."""
    rows_bottom_up = [
        "S......",
        ".######",
        ".......",
        "######.",
        ".......",
        ".######",
        "......G",
    ]
    occ = np.array([[c == "#" for c in row] for row in rows_bottom_up])
    return GridMap(occ)


START, GOAL = (0.5, 0.5), (6.5, 6.5)


@pytest.mark.parametrize("algorithm", ["iga", "ga"])
def test_cell_sequence_ga_doubles_back_in_x(algorithm):
    world = serpentine()
    r = op.plan(world, START, GOAL, algorithm=algorithm, encoding="cells", seed=0, pop=20, iters=30)
    assert r.feasible and validate_path(world, r.path).ok
    dx = np.diff(r.path[:, 0])
    assert (dx > 0).any() and (dx < 0).any()             # it went right and came back left
    optimum = op.shortest_path(world, START, GOAL, method="astar").length
    assert r.length <= optimum + 1e-6 or r.length == pytest.approx(optimum, rel=0.02)


def test_column_chromosome_cannot_represent_the_serpentine():
    with pytest.raises(op.InfeasibleQueryError, match="one cell per column"):
        op.plan(serpentine(), START, GOAL, algorithm="iga", encoding="columns", seed=0, pop=20, iters=30)


def test_cell_sequence_iga_is_reproducible_and_valid_on_a_paper_map():
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("li2023_30")
    a = op.plan(world, s, g, algorithm="iga", encoding="cells", seed=3, pop=20, iters=20)
    b = op.plan(world, s, g, algorithm="iga", encoding="cells", seed=3, pop=20, iters=20)
    assert a.feasible and validate_path(world, a.path).ok
    np.testing.assert_array_equal(a.path, b.path)
    np.testing.assert_array_equal(a.history, b.history)
    c = op.plan(world, s, g, algorithm="iga", encoding="cells", seed=4, pop=20, iters=20)
    assert not np.array_equal(a.history, c.history)


def test_cell_sequence_ga_honours_an_evaluation_budget():
    world, s, g = serpentine(), START, GOAL
    r = op.plan(world, s, g, algorithm="ga", encoding="cells", seed=1, pop=10, iters=None, max_evals=95)
    assert r.nfev == 95


@pytest.mark.parametrize("options", [{"pc": 1.5}, {"pm_range": (0.3, 0.1)}, {"pop": 1}, {"bogus": 1}, {"postprocess": "spline"},
                                     {"alternatives": -1}])
def test_bad_cell_ga_options_raise_parameter_error(options):
    with pytest.raises(op.ParameterError):
        op.plan(serpentine(), START, GOAL, algorithm="iga", encoding="cells", seed=0, iters=5, **options)


def test_drop_loops_cuts_revisits():
    C = np.array([[0, 1, 2, 1, 5, -1], [3, 4, 3, 4, 6, 7]])
    np.testing.assert_array_equal(drop_loops(C), [[0, 1, 5, -1, -1, -1], [3, 4, 6, 7, -1, -1]])


def test_start_and_goal_in_one_cell_give_the_straight_segment():
    r = op.plan(serpentine(), (0.2, 0.2), (0.7, 0.7), algorithm="iga", encoding="cells", seed=0, pop=6, iters=5)
    assert r.feasible
    np.testing.assert_allclose(r.path, [[0.2, 0.2], [0.7, 0.7]])


def test_unreachable_goal_raises_infeasible_query():
    occ = np.zeros((5, 5), bool)
    occ[:, 2] = True                                     # a wall across the map
    with pytest.raises(op.InfeasibleQueryError, match="cannot be reached"):
        op.plan(GridMap(occ), (0.5, 0.5), (4.5, 4.5), algorithm="ga", encoding="cells", seed=0, pop=6, iters=5)


def test_li2023_global_runs_the_paper_chromosome_with_the_columns_next_to_it():
    from optplan.bench.spec import load_spec

    spec = load_spec("li2023_global")
    encodings = {a.label: a.params.get("encoding") for a in spec.algorithms}
    assert encodings == {"ga": "cells", "iga": "cells", "ga-columns": "columns", "iga-columns": "columns",
                         "astar": None}


def test_cell_sequence_iga_refines_and_offers_valid_alternatives():
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("li2023_30")
    r = op.plan(world, s, g, algorithm="iga", encoding="cells", seed=0, pop=30, iters=40, alternatives=2)
    assert r.feasible and r.alternatives
    assert all(validate_path(world, p).ok for p in r.alternatives)
    refined = op.plan(world, s, g, algorithm="iga", encoding="cells", seed=0, pop=30, iters=40, refine="casadi")
    assert refined.feasible and refined.length <= r.length + 1e-9


@pytest.mark.parametrize("algorithm", ["ga", "iga"])
def test_path_gas_fall_back_to_the_cell_sequence_when_columns_cannot_hold_a_path(algorithm):
    """Issue 43: on a rooms map whose path must turn back in x, ga/iga used to end in 'no path
    with one node per column ... try encoding='waypoints'' (which iga refuses); they now plan
    with li2023's general cell sequence and say so, and an explicit encoding='columns' names
    an encoding they take."""
    from optplan.solvers.paths import _columns_represent
    from optplan.worldgen.maps import generate_map, map_query

    grid = generate_map("rooms", 20, 10)
    s, g = map_query(grid, 10)
    assert not _columns_represent(grid, s, g, 0.0)
    # li2023's chromosome: encoding="paper" (both default to the general encoding)
    r = op.plan(grid, s, g, algorithm=algorithm, seed=0, iters=30, encoding="paper")
    assert r.feasible and r.encoding == "cells" and "encoding='cells'" in r.message
    assert op.validate_path(grid, r.path)
    with pytest.raises(op.InfeasibleQueryError, match="encoding='cells'"):
        op.plan(grid, s, g, algorithm=algorithm, encoding="columns", seed=0, iters=30)
