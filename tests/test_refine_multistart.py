"""Multi-start refinement: the best path and other distinct paths of the planner's population."""
from __future__ import annotations

import json

import numpy as np
import pytest

import optplan as op
from optplan.cli import main as cli_main
from optplan.solvers.metaheuristics import optimize
from optplan.solvers.refine import DEFAULT_STARTS, pick_starts, refine_path, refine_result
from optplan.solvers.tube import Band, default_tube_radius, population_alternatives
from optplan.world.metrics import path_length


def wall_world():
    """30 x 20 cells, a wall one cell thick in column 15 from row 2 to row 16. From
    (5.5, 3.5) to (25.5, 3.5) the short way passes below it (about 20.2 m), the long
    way above it (about 34 m), far outside the default tube (2 m) of each other."""
    occ = np.zeros((20, 30), dtype=bool)
    occ[2:17, 15] = True
    return op.GridMap(occ), np.array([5.5, 3.5]), np.array([25.5, 3.5])


OVER_THE_TOP = np.array([[5.5, 3.5], [14.5, 17.5], [16.5, 17.5], [25.5, 3.5]])
UNDER = np.array([[5.5, 3.5], [10.5, 0.5], [20.5, 0.5], [25.5, 3.5]])
THROUGH_THE_WALL = np.array([[5.5, 3.5], [25.5, 3.5]])


def result_with(world, path, alternatives=()):
    res = op.PlanResult("hand", np.asarray(path, float), bool(op.validate_path(world, path)),
                        float(path_length(path)), 0.0, 0, 0.0, 0.0)
    res.alternatives = [np.asarray(a, float) for a in alternatives]
    return res


def test_the_test_world_is_what_it_claims():
    world, s, g = wall_world()
    assert default_tube_radius(world) == pytest.approx(2.0)
    assert op.validate_path(world, OVER_THE_TOP) and op.validate_path(world, UNDER)
    assert not op.validate_path(world, THROUGH_THE_WALL)
    assert not Band(world, OVER_THE_TOP, 2.0).holds(UNDER)           # outside each other's tube
    assert Band(world, UNDER, 2.0).holds(UNDER + [0.0, 0.3])


def test_wrong_corridor_seed_with_an_alternative_in_the_right_one_reaches_the_optimum():
    world, s, g = wall_world()
    opt = op.shortest_path(world, s, g, method="visibility").length
    res = result_with(world, OVER_THE_TOP, [UNDER])
    single = refine_result(world, res, "casadi", starts=1)
    multi = refine_result(world, res, "casadi")                     # default: 3 starts
    assert DEFAULT_STARTS["casadi"] == 3
    assert single.refined and single.length > 1.3 * opt             # the tube cannot reach the other side
    assert multi.refined and multi.feasible and op.validate_path(world, multi.path)
    assert opt - 1e-9 <= multi.length <= 1.01 * opt
    assert np.all(multi.path[:, 1] <= 3.5 + 1e-6)                     # it passes below the wall
    assert "start 2 of 2" in multi.message
    assert multi.runtime_s > single.runtime_s * 0.5                   # both starts are counted, not only the winner


def test_one_start_is_the_single_start_refinement_exactly():
    world, s, g = wall_world()
    with_alt = refine_result(world, result_with(world, OVER_THE_TOP, [UNDER]), "casadi", starts=1)
    without = refine_result(world, result_with(world, OVER_THE_TOP), "casadi")
    direct = refine_path(world, OVER_THE_TOP, "casadi")
    np.testing.assert_array_equal(with_alt.path, without.path)
    np.testing.assert_array_equal(with_alt.path, direct.path)
    assert with_alt.message == without.message == direct.message
    # a planner asked for one start is not asked for alternatives, and gives the same refined path
    grid, s, g = _paper("li2023_11")
    one = op.plan(grid, s, g, algorithm="missa", seed=1, pop=12, iters=15, refine="casadi",
                  refine_options={"starts": 1})
    pure = op.plan(grid, s, g, algorithm="missa", seed=1, pop=12, iters=15)
    assert one.alternatives == [] and pure.alternatives == []
    np.testing.assert_allclose(one.path, refine_path(grid, pure.path, "casadi").path, atol=1e-9)


def _paper(name):
    from optplan.world.papermaps import paper_map

    return paper_map(name)


def test_alternatives_never_include_an_invalid_or_repeated_path():
    world, s, g = wall_world()
    cands = [OVER_THE_TOP, THROUGH_THE_WALL, OVER_THE_TOP + [0.0, 0.2], UNDER, UNDER + [0.0, 0.4]]
    kept = population_alternatives(world, cands, OVER_THE_TOP, count=5, separation=2.0)
    assert len(kept) == 1 and np.array_equal(kept[0], UNDER)        # the wall-crosser and near-copies are out
    kept0 = population_alternatives(world, cands, OVER_THE_TOP, count=5, separation=0.0)
    assert [op.validate_path(world, k).ok for k in kept0] == [True] * 3   # any distinct valid path
    # from a real planner: every alternative validates, lies outside the others' bands, leaves the path unchanged
    grid, s, g = _paper("chen2025_20")
    pure = op.plan(grid, s, g, algorithm="gwo", seed=3, pop=20, iters=40)
    res = op.plan(grid, s, g, algorithm="gwo", seed=3, pop=20, iters=40, alternatives=4, alternative_separation=1.0)
    np.testing.assert_array_equal(res.path, pure.path)
    assert res.nfev == pure.nfev and 1 <= len(res.alternatives) <= 4
    seen = [res.path]
    for alt in res.alternatives:
        assert op.validate_path(grid, alt)
        assert not any(Band(grid, q, 1.0).holds(alt) for q in seen)
        seen.append(alt)


def test_a_colliding_alternative_never_comes_back_unchecked():
    world, s, g = wall_world()
    res = refine_result(world, result_with(world, OVER_THE_TOP, [THROUGH_THE_WALL]), "qp", starts=2)
    assert res.feasible and op.validate_path(world, res.path)        # qp cannot repair it: the best path's result wins
    picked = pick_starts(world, result_with(world, OVER_THE_TOP, [OVER_THE_TOP + [0, 0.5], UNDER]), 5, 2.0)
    assert len(picked) == 1 and np.array_equal(picked[0], UNDER)


def test_the_ga_offers_alternatives_too_and_plan_is_reproducible():
    grid, s, g = _paper("li2023_11")
    a = op.plan(grid, s, g, algorithm="iga", seed=4, pop=20, iters=30, refine="casadi")
    b = op.plan(grid, s, g, algorithm="iga", seed=4, pop=20, iters=30, refine="casadi")
    np.testing.assert_array_equal(a.path, b.path)
    assert a.message == b.message and len(a.alternatives) == len(b.alternatives)
    for x, y in zip(a.alternatives, b.alternatives):
        np.testing.assert_array_equal(x, y)
        assert op.validate_path(grid, x)
    assert a.feasible and a.refined


def test_alternatives_stay_out_of_dicts_and_json():
    grid, s, g = _paper("li2023_11")
    res = op.plan(grid, s, g, algorithm="gwo", seed=0, pop=10, iters=10, alternatives=2)
    assert "alternatives" not in res.to_dict()
    assert set(res.to_json_dict()) == set(op.PlanResult.JSON_KEYS)
    json.dumps(res.to_dict())


def test_engine_archive_costs_no_evaluation_and_is_ranked():
    f = lambda X: np.sum((X - 0.3) ** 2, axis=1)  # noqa: E731
    plain = optimize(f, [(-1, 1)] * 3, algorithm="gwo", pop=8, iters=12, seed=2)
    kept = optimize(f, [(-1, 1)] * 3, algorithm="gwo", pop=8, iters=12, seed=2, archive_every=4)
    assert plain.archive is None and "archive" not in kept.to_dict()
    assert kept.nfev == plain.nfev and kept.f == plain.f
    X, F, V = kept.archive
    assert len(np.unique(X, axis=0)) == len(X) and len(X) > 8
    np.testing.assert_allclose(F, f(X))
    assert np.all(np.diff(F) >= 0) and np.all(V == 0)


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, "3", 51])
def test_bad_starts_are_refused_before_planning(bad):
    grid, s, g = _paper("li2023_11")
    with pytest.raises(op.ParameterError, match="starts"):
        op.plan(grid, s, g, algorithm="gwo", refine="casadi", refine_options={"starts": bad})


def test_other_bad_values_are_refused():
    grid, s, g = _paper("li2023_11")
    with pytest.raises(op.ParameterError, match="alternatives"):
        op.plan(grid, s, g, algorithm="gwo", pop=5, iters=2, alternatives=-1)
    with pytest.raises(op.ParameterError, match="alternative_separation"):
        op.plan(grid, s, g, algorithm="gwo", pop=5, iters=2, alternatives=1, alternative_separation=float("nan"))
    with pytest.raises(op.ParameterError, match="archive_every"):
        optimize(lambda X: X.sum(axis=1), [(0, 1)] * 2, pop=4, iters=2, archive_every=0)


def test_cli_refine_starts(capsys):
    base = ["plan", "li2023_11", "--start", "0.5", "0.5", "--goal", "10.5", "10.5", "--algo", "gwo",
            "--pop", "10", "--iters", "10"]
    assert cli_main(base + ["--refine", "casadi", "--refine-starts", "2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["refined"] and out["feasible"]
    assert cli_main(base + ["--refine", "casadi", "--refine-starts", "0"]) == 2
    assert "starts must be an integer" in capsys.readouterr().err
    assert cli_main(base + ["--refine-starts", "2"]) == 2
    assert "--refine-starts only applies" in capsys.readouterr().err
