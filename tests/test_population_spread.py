"""li2023 Fig 14's diversity: the GAs report their population's fitness spread per generation,
and a plan run stores its mean (the ``fitness_spread`` metric of li2023_global's claims)."""
from __future__ import annotations

import numpy as np

import optplan as op
from optplan.solvers.gridpath.ga_path import fitness_spread
from optplan.world.papermaps import paper_map


def test_fitness_spread_is_the_std_of_the_finite_values():
    assert fitness_spread(np.array([1.0, 3.0, np.inf])) == 1.0
    assert fitness_spread(np.array([2.0, np.inf])) == 0.0


def test_the_gas_report_one_spread_per_generation():
    world, s, g = paper_map("li2023_30")
    for algorithm in ("ga", "iga"):
        r = op.plan(world, s, g, algorithm=algorithm, encoding="cells", pop=20, iters=15, seed=3)
        assert len(r.population_spread) == len(r.history) and np.all(r.population_spread >= 0)
        again = op.plan(world, s, g, algorithm=algorithm, encoding="cells", pop=20, iters=15, seed=3)
        assert np.array_equal(r.population_spread, again.population_spread)
    other = op.plan(world, s, g, algorithm="pso", pop=10, iters=5, seed=0)
    assert len(other.population_spread) == 0


def test_a_plan_run_stores_the_mean_spread():
    from optplan.bench.kinds.plan import PlanKind

    assert "fitness_spread" in PlanKind.extra_metrics
