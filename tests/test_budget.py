"""The one Budget every population loop obeys (issue 25): the engine, ACO and the path GAs."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan.formulations.functions import get_function
from optplan.solvers import paths
from optplan.solvers.budget import Budget, BudgetExhausted
from optplan.world.papermaps import paper_map

RASTRIGIN = get_function("F9", shifted=True, dim=5)


def population_planners() -> list[str]:
    """Every planner of ``op.algorithms()`` that runs a population loop (all but graph search)."""
    return [name for name in op.algorithms() if name in paths.algorithm_names()]


def test_the_planner_list_covers_the_three_loops():
    names = population_planners()
    assert {"aco", "ga", "iga", "ssa", "missa", "gwo", "pso"} <= set(names)


@pytest.mark.parametrize("name", population_planners())
def test_every_population_planner_spends_max_evals_exactly(name):
    """``max_evals=200`` gives ``nfev == 200`` for every population planner on a grid
    (ACO cuts its last colony, the GAs their last generation, the engine its last batch)."""
    world, s, g = paper_map("chen2025_20")
    r = op.plan(world, s, g, algorithm=name, seed=0, pop=30, max_evals=200)
    assert r.nfev == 200
    again = op.plan(world, s, g, algorithm=name, seed=0, pop=30, max_evals=200)
    np.testing.assert_array_equal(r.path, again.path)


@pytest.mark.parametrize("name", ["ga", "pso", "missa"])
def test_circle_world_planners_spend_max_evals_exactly(name):
    world = op.CircleWorld(bounds=(0, 0, 10, 10), circles=[(5, 5, 1.5), (3, 7, 1.0)])
    r = op.plan(world, (0.5, 0.5), (9.5, 9.5), algorithm=name, seed=1, pop=20, max_evals=333)
    assert r.nfev == 333


def test_aco_cuts_its_last_colony_to_the_budget():
    from optplan.solvers.gridpath.aco import aco_path

    world, s, g = paper_map("chen2025_20")
    _, hist, nfev = aco_path(world, s, g, ants=60, iters=None, max_evals=250, seed=0)
    assert nfev == 250
    assert len(hist) == 1 + math.ceil(250 / 60)       # 60, 60, 60, 60, 10 ants
    # the iteration cap still binds when it comes first
    _, hist, nfev = aco_path(world, s, g, ants=60, iters=2, max_evals=250, seed=0)
    assert nfev == 120 and len(hist) == 3


def test_budget_progress_and_horizon():
    b = Budget(iterations=100, evaluations=1000)
    assert b.progress(10, 50) == pytest.approx(0.1)      # iterations lead
    assert b.progress(10, 500) == pytest.approx(0.5)     # evaluations lead
    assert b.progress(500, 5000) == 1.0
    assert Budget(evaluations=15030).horizon(30) == 500
    assert Budget(iterations=0).horizon(30) == 1
    assert Budget(iterations=7).progress(7, 10**9) == 1.0


def test_budget_cuts_batches_and_says_why_it_stops():
    b = Budget(evaluations=100, stagnation=5, target=0.0)
    assert b.allowed(30, 0) == 30 and b.allowed(30, 90) == 10
    with pytest.raises(BudgetExhausted):
        b.allowed(30, 100)
    assert b.stop(3, 50) is None
    assert b.stop(3, 100)[0] == "max_evals"
    assert b.stop(3, 50, since_improvement=5)[0] == "stagnation"
    assert b.stop(3, 100, best=-1.0)[0] == "target"              # the target outranks the limits
    assert b.stop(3, 50, best=-1.0, best_feasible=False) is None  # infeasible bests never reach it
    assert Budget(iterations=4).stop(4, 0)[0] == "max_iters"


@pytest.mark.parametrize("kwargs, match", [
    ({}, "unbounded"),
    ({"iterations": -1}, "iters"),
    ({"iterations": 2.5}, "iters"),
    ({"evaluations": 0}, "max_evals"),
    ({"iterations": 5, "stagnation": 0}, "stagnation"),
    ({"iterations": 5, "target": float("nan")}, "target"),
])
def test_bad_budgets_raise_parameter_errors(kwargs, match):
    with pytest.raises(op.ParameterError, match=match):
        Budget(**kwargs)


def test_optimize_takes_a_budget_object_with_the_same_numbers():
    kw = dict(algorithm="gwo", pop=10, seed=4)
    a = op.optimize(RASTRIGIN, RASTRIGIN.bounds, iters=None, max_evals=555, stagnation=30, **kw)
    b = op.optimize(RASTRIGIN, RASTRIGIN.bounds, budget=Budget(evaluations=555, stagnation=30), **kw)
    np.testing.assert_array_equal(a.history, b.history)
    assert a.nfev == b.nfev and a.status == b.status
    with pytest.raises(op.ParameterError, match="not both"):
        op.optimize(RASTRIGIN, RASTRIGIN.bounds, max_evals=100, budget=Budget(evaluations=100), **kw)
    with pytest.raises(op.ParameterError, match="Budget"):
        op.optimize(RASTRIGIN, RASTRIGIN.bounds, budget={"evaluations": 100}, **kw)
