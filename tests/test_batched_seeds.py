"""``op.optimize(..., seeds=...)``: R independent runs, batched as one R x pop population
where the algorithm allows, each identical to its single run bit for bit (issue 30)."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.formulations.functions import get_function
from optplan.solvers.metaheuristics import get_algorithm

RASTRIGIN = get_function("F9", shifted=True, dim=8)


def assert_same_run(batched, single):
    np.testing.assert_array_equal(batched.history, single.history)
    np.testing.assert_array_equal(batched.history_nfev, single.history_nfev)
    np.testing.assert_array_equal(batched.x, single.x)
    assert batched.f == single.f and batched.nfev == single.nfev and batched.nit == single.nit
    assert batched.status == single.status and batched.message == single.message
    assert batched.seed == single.seed


@pytest.mark.parametrize("algorithm", ["gwo", "pso"])
@pytest.mark.parametrize("budget", [dict(iters=40), dict(iters=None, max_evals=1111), dict(iters=25, max_evals=500)])
def test_batched_seeds_equal_separate_runs_bit_for_bit(algorithm, budget):
    assert get_algorithm(algorithm).batchable()
    calls = []

    def f(X):
        calls.append(len(X))
        return RASTRIGIN(X)

    runs = op.optimize(f, RASTRIGIN.bounds, algorithm=algorithm, pop=12, seeds=range(6), **budget)
    assert isinstance(runs, list) and len(runs) == 6
    assert max(calls) == 6 * 12                     # one objective call holds every run's rows
    for s, r in enumerate(runs):
        assert_same_run(r, op.optimize(RASTRIGIN, RASTRIGIN.bounds, algorithm=algorithm, pop=12, seed=s, **budget))
    assert len({r.f for r in runs}) == 6            # the runs are independent


def test_batched_runs_keep_constraints_repair_and_initialisers():
    def f(X):
        return RASTRIGIN(X), np.maximum(X[:, 0] - 1.0, 0.0)     # feasible when x0 <= 1

    def repair(X):
        return np.round(X, 1)

    def init(n, rng):
        return rng.uniform(-2, 2, (n, RASTRIGIN.dim))

    kw = dict(algorithm="gwo", pop=10, iters=30, repair=repair, init=init)
    runs = op.optimize(f, RASTRIGIN.bounds, seeds=[3, 1, 4], **kw)
    for s, r in zip([3, 1, 4], runs):
        assert_same_run(r, op.optimize(f, RASTRIGIN.bounds, seed=s, **kw))
        assert r.x[0] <= 1.0


@pytest.mark.parametrize("algorithm", ["ssa", "msiar-gwo", "ipso"])
def test_other_algorithms_run_the_seeds_one_by_one_with_the_same_numbers(algorithm):
    assert not get_algorithm(algorithm).batchable()       # BATCHABLE is not inherited
    runs = op.optimize(RASTRIGIN, RASTRIGIN.bounds, algorithm=algorithm, pop=10, iters=15, seeds=range(3))
    for s, r in enumerate(runs):
        assert_same_run(r, op.optimize(RASTRIGIN, RASTRIGIN.bounds, algorithm=algorithm, pop=10, iters=15, seed=s))


def test_per_run_stops_fall_back_to_separate_runs():
    kw = dict(algorithm="gwo", pop=10, iters=200, stagnation=5)
    runs = op.optimize(RASTRIGIN, RASTRIGIN.bounds, seeds=range(3), **kw)
    for s, r in enumerate(runs):
        assert_same_run(r, op.optimize(RASTRIGIN, RASTRIGIN.bounds, seed=s, **kw))


@pytest.mark.parametrize("seeds, match", [(5, "iterable"), ([], "empty"), ([0, -1], "seed")])
def test_bad_seeds_raise_parameter_errors(seeds, match):
    with pytest.raises(op.ParameterError, match=match):
        op.optimize(RASTRIGIN, RASTRIGIN.bounds, algorithm="gwo", pop=10, iters=5, seeds=seeds)


@pytest.mark.parametrize("algorithm", ["gwo", "pso"])
def test_a_batch_of_one_is_the_single_run(algorithm):
    # one loop drives both: a batch of one seed is the single run, number for number
    (batched,) = op.optimize(RASTRIGIN, RASTRIGIN.bounds, algorithm=algorithm, pop=9, iters=None, max_evals=400,
                             seeds=[7])
    assert_same_run(batched, op.optimize(RASTRIGIN, RASTRIGIN.bounds, algorithm=algorithm, pop=9, iters=None,
                                         max_evals=400, seed=7))


def test_generators_given_as_seeds_end_where_their_single_runs_leave_them():
    # int seeds' generators read ahead in large blocks; a caller's Generator is not read
    # ahead, so it can go on drawing exactly as after a single run
    kw = dict(algorithm="gwo", pop=8, iters=12)
    given = [np.random.default_rng(11), np.random.default_rng(12)]
    runs = op.optimize(RASTRIGIN, RASTRIGIN.bounds, seeds=given, **kw)
    for s, g, r in zip((11, 12), given, runs):
        alone = np.random.default_rng(s)
        assert_same_run(r, op.optimize(RASTRIGIN, RASTRIGIN.bounds, seed=alone, **kw))
        assert g.bit_generator.state == alone.bit_generator.state


def test_one_generator_given_twice_runs_the_seeds_one_after_the_other():
    kw = dict(algorithm="gwo", pop=8, iters=10)
    g = np.random.default_rng(5)
    runs = op.optimize(RASTRIGIN, RASTRIGIN.bounds, seeds=[g, g], **kw)
    h = np.random.default_rng(5)
    for r in runs:
        assert_same_run(r, op.optimize(RASTRIGIN, RASTRIGIN.bounds, seed=h, **kw))


def test_read_ahead_streams_refuse_other_kinds_of_draws():
    from optplan.solvers.metaheuristics.engine import SeedGenerators

    rng = SeedGenerators(range(3))
    first = rng.random((2, 5)).copy()
    np.testing.assert_array_equal(first[1], np.random.default_rng(1).random((2, 5)))
    with pytest.raises(RuntimeError, match="read ahead"):
        rng.normal(size=4)
    many = SeedGenerators(range(4096))          # many seeds read ahead less (a bounded block)
    for _ in range(7):                          # the seventh refills, keeping the 50 pending
        many.random((7, 11))
    assert many._ahead.nbytes <= SeedGenerators.READ_AHEAD_TOTAL * 8
    np.testing.assert_array_equal(many.random(9)[4095], np.random.default_rng(4095).random(7 * 77 + 9)[-9:])


STEP = get_function("F6", dim=8)      # a plateau: many wolves tie


@pytest.mark.parametrize("constrained", [False, True])
def test_batched_gwo_breaks_ties_as_each_single_run_does(constrained):
    # the single run's leader update breaks ties in its own way (top three by argpartition,
    # or the feasibility ranking when something is violated); a batched run follows each
    # run's own rule (it used to give seeds 1, 4 and 5 other leaders on F6)
    def f(X):
        return (STEP(X), np.maximum(X[:, 0] - 50.0, 0.0)) if constrained else STEP(X)

    kw = dict(algorithm="gwo", pop=12, iters=60)
    runs = op.optimize(f, STEP.bounds, seeds=range(6), **kw)
    for s, r in enumerate(runs):
        assert_same_run(r, op.optimize(f, STEP.bounds, seed=s, **kw))


@pytest.mark.slow
@pytest.mark.parametrize("algorithm", ["gwo", "pso"])
def test_batched_equals_separate_on_held_out_seeds(algorithm):
    # seeds never looked at while the batched path was written (before the tie fix: 793/800)
    seeds = list(range(1000, 1020))
    for name in ("F1", "F5", "F6", "F9", "F12"):
        F = get_function(name, shifted=True, dim=10)
        for constrained in (False, True):
            def f(X, F=F, constrained=constrained):
                return (F(X), np.maximum(X[:, 1] - 0.3 * F.bounds[1][1], 0.0)) if constrained else F(X)

            for budget in (dict(iters=40), dict(iters=None, max_evals=517)):
                runs = op.optimize(f, F.bounds, algorithm=algorithm, pop=11, seeds=seeds, **budget)
                for s, r in zip(seeds, runs):
                    assert_same_run(r, op.optimize(f, F.bounds, algorithm=algorithm, pop=11, seed=s, **budget))
