"""Path formulations: decoding, shared terms, table lookups equal to the exact rule."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.formulations import terms
from optplan.formulations.encodings import ColumnNodes, FreeWaypoints, SplinePath
from optplan.formulations.presets import PRESETS, get_preset
from optplan.formulations.problem import PathProblem


@pytest.fixture(scope="module")
def grid():
    return op.load_map("multialgo20_template")


def test_column_nodes_decode_to_cell_centres(grid):
    enc = ColumnNodes(grid, np.array([0.5, 0.5]), np.array([19.5, 19.5]))
    assert enc.dim == 18
    X = np.full((2, 18), 3.7)
    P = enc.decode(X)
    assert P.shape == (2, 20, 2)
    np.testing.assert_array_equal(P[0, 1:-1, 1], 3.5)
    np.testing.assert_array_equal(P[0, 1:-1, 0], np.arange(1, 19) + 0.5)
    # right to left also works
    back = ColumnNodes(grid, np.array([19.5, 0.5]), np.array([0.5, 19.5]))
    assert back.decode(X)[0, 1, 0] == 18.5


@pytest.mark.parametrize("clearance", [0.0, 0.3])
def test_table_lookup_equals_exact_rule(grid, clearance):
    enc = ColumnNodes(grid, np.array([0.5, 0.5]), np.array([19.5, 19.5]))
    X = np.random.default_rng(2).uniform(0, 20, (200, enc.dim))
    tables = enc.segment_tables(clearance)
    np.testing.assert_array_equal(enc.lookup(tables, X), terms.collisions(grid, enc.decode(X), clearance))


def test_problem_penalty_and_feasibility_modes(grid):
    enc = ColumnNodes(grid, np.array([0.5, 0.5]), np.array([19.5, 19.5]))
    X = np.random.default_rng(3).uniform(0, 20, (50, enc.dim))
    pen = PathProblem(enc, "hou2024")
    fea = PathProblem(enc, "hou2024", constraint="feasibility")
    f1, v1 = pen.evaluate(X)
    f2, v2 = fea.evaluate(X)
    np.testing.assert_allclose(v1, v2)
    np.testing.assert_allclose(f2, terms.length(enc.decode(X)))
    assert np.all(f1 >= f2) and np.all((f1 > f2) == (v1 > 0))
    # zero violation exactly when every decoded path passes the exact check
    ok = np.array([bool(op.validate_path(grid, p)) for p in enc.decode(X)])
    np.testing.assert_array_equal(v1 == 0, ok)


def test_chen2025_penalty_is_goal_product(grid):
    enc = ColumnNodes(grid, np.array([0.5, 0.5]), np.array([19.5, 19.5]))
    prob = PathProblem(enc, "chen2025")
    X = np.random.default_rng(4).uniform(0, 20, (20, enc.dim))
    f, v = prob.evaluate(X)
    np.testing.assert_allclose(f, terms.length(enc.decode(X)) + 400.0 * v)


def test_spline_and_waypoints_on_circles():
    w = op.CircleWorld((0, 0, 10, 10), [(5, 5, 1.5)], safety=0.2)
    s, g = np.array([0.0, 0.0]), np.array([10.0, 10.0])
    spl = SplinePath(w, s, g, m=3, samples=50)
    wp = FreeWaypoints(w, s, g, m=3)
    straight = np.tile(np.linspace(2.5, 7.5, 3)[:, None], (1, 2)).ravel()[None, :]
    for enc in (spl, wp):
        prob = PathProblem(enc, "yang2023", constraint="feasibility")
        f, v = prob.evaluate(straight)
        assert v[0] > 0  # through the obstacle
        assert f[0] == pytest.approx(np.hypot(10, 10), rel=1e-6)
    around = np.array([[2.0, 6.5, 3.5, 8.5, 6.0, 9.5]])
    assert PathProblem(wp, "yang2023").evaluate(around)[1][0] == 0


def test_turn_terms():
    P = np.array([[[0, 0], [1, 0], [2, 1], [2, 2]]], float)
    assert terms.turn_angle(P)[0] == pytest.approx(np.pi / 2)
    assert terms.turn_count(P)[0] == 2
    assert terms.turn_cost_quantised(P)[0] == pytest.approx(2 * np.pi / 4)


def test_presets_cite_sources():
    for p in PRESETS.values():
        assert p.source
    with pytest.raises(op.UnknownAlgorithmError):
        get_preset("nope")


@pytest.mark.parametrize("preset", ["li2023", "yuan2021-smooth", "chen2025"])
@pytest.mark.parametrize("constraint", ["penalty", "feasibility"])
def test_tabulated_column_scores_equal_decoded_path_scores(grid, preset, constraint):
    """Per-segment tables (length, collisions, headings) give the same objective as the
    shared terms on decoded paths, turn terms included."""
    enc = ColumnNodes(grid, np.array([0.5, 0.5]), np.array([19.5, 19.5]))
    X = np.random.default_rng(5).uniform(0, 20, (80, enc.dim))
    prob = PathProblem(enc, preset, constraint=constraint, clearance=0.2)
    f, v = prob.evaluate(X)
    paths = enc.decode(X)
    expected = prob.cost_terms(paths)
    coll = terms.collisions(grid, paths, 0.2)
    pen = v - coll                       # violation = collision count + penetration
    assert np.all(pen >= -1e-12)
    if constraint == "penalty":
        expected = expected + prob._collision_penalty * coll + prob.preset.penetration_penalty * pen
    np.testing.assert_allclose(f, expected, rtol=1e-12, atol=1e-9)


def test_column_dynamic_programme_finds_the_shortest_expressible_path():
    """optimal_rows equals brute force over every row choice on a small map."""
    import itertools

    g = op.GridMap.from_rows([[0, 0, 0, 0, 0, 0], [0, 1, 1, 0, 1, 0], [0, 0, 0, 0, 1, 0],
                              [0, 1, 0, 0, 0, 0], [0, 0, 0, 1, 0, 0]])
    enc = ColumnNodes(g, np.array([0.5, 0.5]), np.array([5.5, 4.5]))
    cost, rows = enc.optimal_rows()
    choices = np.array(list(itertools.product(range(g.height), repeat=enc.dim))) + 0.5
    paths = enc.decode(choices)
    ok = np.array([bool(op.validate_path(g, p)) for p in paths])
    L = terms.length(paths)
    assert cost == pytest.approx(L[ok].min(), rel=1e-12)
    assert op.validate_path(g, enc.waypoints(rows + 0.5))
    assert terms.length(enc.decode(rows[None] + 0.5))[0] == pytest.approx(cost, rel=1e-12)


def test_segment_tables_are_shared_by_map_content_only():
    """A reloaded copy of a map reuses its tables; another map of the same size does not."""
    s, g = np.array([0.5, 0.5]), np.array([29.5, 29.5])
    a = ColumnNodes(op.load_map("li2023_30"), s, g).segment_tables(0.0)
    again = ColumnNodes(op.load_map("li2023_30"), s, g).segment_tables(0.0)
    other_world = op.load_map("chen2025_30")
    other = ColumnNodes(other_world, s, g).segment_tables(0.0)
    assert again is a and other is not a
    X = np.random.default_rng(0).uniform(0, 30, (100, 28))
    enc = ColumnNodes(other_world, s, g)
    np.testing.assert_array_equal(enc.lookup(other, X), terms.collisions(other_world, enc.decode(X)))
